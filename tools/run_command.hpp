#pragma once
/// @file
/// `lagrange run`: validate the scenario, enter a private network namespace,
/// start plant, actuator, controller and logger, show progress, stop
/// everything cleanly, and report.

#include <string>
#include <vector>

namespace lagrange::tools {

struct RunOptions {
  std::string config_path;
  std::string out_dir;
  std::vector<std::string> overrides;
  bool private_netns = true;
  std::string lcm_url;  ///< empty: a fresh URL per run
  bool strict = false;
  bool quiet = false;
  bool report = false;                 ///< write OUT/report (CSV + plots) when the run ends with a log
  std::vector<std::string> self_argv;  ///< to re-execute inside the namespace
};

/// Exit code: 0 success, 1 a process failed, 2 bad input, 130 interrupted.
int runScenario(const RunOptions& options);

}  // namespace lagrange::tools
