#pragma once
/// @file
/// `lagrange check-gains CONFIG [--set key=value ...] [--suggest]`: the gain
/// conditions of a scenario's controller and the sampled-data check, without
/// running it (the verdicts are controller::checkGains's, controller/gain_report.hpp).

#include <string>
#include <vector>

#include "tools/subcommand.hpp"

namespace lagrange::tools {

/// Prints the report (and with `suggest` the paper's gains and their report).
/// With `simulate`, the sampled-data verdict by simulation too
/// (wiring/sampled_simulation.hpp). Exit 0 when the conditions hold, 1 when
/// one is violated, the sampled loop diverges in simulation or is unstable
/// near the reference, or no suggestion passes, 2 for a bad scenario.
int checkGainsCommand(const std::string& config_path, const std::vector<std::string>& overrides, bool suggest,
                      bool simulate = true);

/// Declares `check-gains` on the front end.
Subcommand addCheckGainsCommand(CLI::App& app);

}  // namespace lagrange::tools
