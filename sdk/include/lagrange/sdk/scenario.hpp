#pragma once
/// @file
/// The run's resolved scenario, parsed, for a controller built with
/// lagrange's C++ SDK: the gains, the joints, the arm's parameters as the
/// run resolved them (every default filled in). `lagrange run` and
/// `lagrange replay` hand it over as JSON (LAGRANGE_CONFIG_JSON,
/// OUT/config.resolved.json; docs/external_controllers.md), numbers as
/// numbers:
///
///     const nlohmann::json s = lagrange::sdk::scenario();
///     std::vector<double> qd = s["reference"]["offset"];
///     double step = s["plant"]["physics_step"];
///
/// nlohmann/json (Debian: nlohmann-json3-dev) comes with the package's
/// lagrange::sdk target; a program that never includes this header needs
/// nothing of it.

#include <nlohmann/json.hpp>

namespace lagrange::sdk {

/// Reads and parses the file LAGRANGE_CONFIG_JSON names. @throws
/// ContractError naming the variable or the file and what was wrong (not
/// set: not started by lagrange; unreadable; not JSON; not an object).
nlohmann::json scenario();

}  // namespace lagrange::sdk
