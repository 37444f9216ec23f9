#pragma once
/// @file
/// The run's resolved scenario, parsed, for a controller built with
/// lagrange's C++ SDK: the gains, the joints, the arm's parameters as the
/// run resolved them (every default filled in). `lagrange run` and
/// `lagrange replay` hand it over as JSON (LAGRANGE_CONFIG_JSON,
/// OUT/config.resolved.json; docs/external_programs.md), numbers as
/// numbers:
///
///     const nlohmann::json s = lagrange::sdk::scenario();
///     std::vector<double> qd = s["reference"]["offset"];
///     double step = s["plant"]["physics_step"];
///
/// Header-only, on nlohmann/json (Debian: nlohmann-json3-dev), which a
/// program that includes this header brings itself
/// (`find_package(nlohmann_json)`, `nlohmann_json::nlohmann_json`): the SDK's
/// library needs none of it, and no nlohmann::json crosses a library
/// boundary built with another version of it.

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "lagrange/sdk/external_controller.hpp"

namespace lagrange::sdk {

/// Reads and parses the file LAGRANGE_CONFIG_JSON names. @throws
/// ContractError naming the variable or the file and what was wrong (not
/// set: not started by lagrange; unreadable; not JSON; not an object).
inline nlohmann::json scenario() {
  const char* path = std::getenv("LAGRANGE_CONFIG_JSON");
  if (path == nullptr || *path == '\0')
    throw ContractError(
        "LAGRANGE_CONFIG_JSON is not set: the resolved scenario is handed over by `lagrange run` and "
        "`lagrange replay` to a program in the controller's or the plant's place (controller.type or "
        "plant.type external)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ContractError(std::string("cannot read the scenario ") + path + " (LAGRANGE_CONFIG_JSON)");
  std::ostringstream text;
  text << in.rdbuf();
  nlohmann::json s = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
  if (s.is_discarded() || !s.is_object())
    throw ContractError(std::string("the scenario ") + path +
                        " (LAGRANGE_CONFIG_JSON) is not a JSON object; expected the config.resolved.json "
                        "lagrange writes");
  return s;
}

}  // namespace lagrange::sdk
