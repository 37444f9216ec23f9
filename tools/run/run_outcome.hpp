#pragma once
/// @file
/// What `lagrange run` says about a finished run, from the logger's
/// summary.json (docs/summary.md lists its fields): the result block it
/// prints, and the stated metrics `--check` finds missed. Pure: the caller
/// reads the file and prints.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lagrange::tools {

/// The result block: scenario and status, final error, convergence time
/// against the deadline, max |torque|, the gain condition (or why it is not
/// checked), sim and wall time.
/// @throws nlohmann::json::exception when a field it prints is missing.
std::string resultText(const nlohmann::json& summary);

/// One line per stated metric the run missed (tracking.met false): the
/// tracking error, and for a chain each stage that did not converge by the
/// deadline, each with its value; empty when tracking.met is true.
/// @throws nlohmann::json::exception when the tracking fields are missing.
std::vector<std::string> missedMetrics(const nlohmann::json& summary);

}  // namespace lagrange::tools
