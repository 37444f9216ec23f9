#pragma once
/// @file
/// `lagrange run`: validate the scenario, enter a private network namespace,
/// start plant, actuator, controller and logger, show progress, stop
/// everything cleanly, and report.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tools/subcommand.hpp"

namespace lagrange::tools {

struct RunOptions {
  std::string config_path;
  std::string out_dir;
  std::vector<std::string> overrides;
  bool private_netns = true;
  std::string lcm_url;  ///< empty: a fresh URL per run
  bool strict = false;
  /// Simulate the sampled loop against a fine-rate one before the run
  /// (wiring::simulateSampledData; seconds); with --strict, refuse on DIVERGES.
  bool check_sampled = false;
  bool quiet = false;
  bool report = false;  ///< write OUT/report (CSV + plots) when the run ends with a log
  bool share = false;   ///< keep the user's umask (else the run's folder 0700, its files 0600)
  /// Exit 3 when the run completed but missed a check (tools/run/metric_checks.hpp):
  /// --check alone is {"met"}, the scenario's stated metric.
  bool check = false;
  std::vector<std::string> checks;
  /// --junit FILE: the checks' results as JUnit XML (implies --check's "met" when no check is named).
  std::string junit_path;
  /// The processes to start on this host (a run spread over several hosts);
  /// empty: all four. A subset needs --no-netns and an explicit LCM URL.
  std::vector<std::string> processes;
  /// The run's identity on every message; unset: random, or for --processes
  /// derived from the LCM URL and the resolved scenario (the same on every host).
  std::optional<int64_t> run_id;
  /// A secret key file shared by runs or hosts (runtime/key_file.hpp): the
  /// run's key is derived from it and a value fresh for this run (with
  /// --processes, agreed between the launchers). Empty: a fresh random key.
  /// Either way the processes get OUT/run.key, removed when the run ends.
  /// Required with --processes.
  std::string key_file;
  /// --processes: how long [s] the launchers wait for each other before the run.
  double join_timeout = 60.0;
  /// False only in the benchmark's build of the front end
  /// (LAGRANGE_BENCH_UNSIGNED, bench/CMakeLists.txt), which measures what the
  /// MAC costs: no key, nothing signed or checked. Never a user option.
  bool sign = true;
  std::vector<std::string> self_argv;  ///< to re-execute inside the namespace
};

/// The processes of a run, in start order: the logger first, so it records from the first tick.
inline const std::vector<std::string> kProcesses = {"logger", "controller", "actuator", "plant"};

/// Exit code: 0 success, 1 a process failed (or the plant stopped a diverging
/// run), 2 bad input, 3 with --check: the run completed but missed its stated
/// metric, 130 interrupted.
int runScenario(const RunOptions& options);

/// Declares `run` and its options on the front end (tools/run/run_cli.cpp).
Subcommand addRunCommand(CLI::App& app);

}  // namespace lagrange::tools
