#pragma once
/// @file
/// `lagrange compare`: the same scenario for several controllers, each tuned
/// by its own section (compare.controllers.TYPE), run in-process as separate
/// `lagrange run --mode inproc` processes, several at a time; then a table of
/// the numbers users compare controllers by, as Markdown and CSV, overlay
/// plots of the tracking error and the torques, and -- with a sweep of one
/// key (a sensor parameter, the sampling rate) -- the steady-state error
/// against that key, one curve per controller. docs/comparison.md.

#include <optional>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "tools/subcommand.hpp"

namespace lagrange::tools {

struct CompareOptions {
  std::string config_path;
  std::string out_dir;
  /// Types to compare, in order; empty: every controller of compare.controllers.
  std::vector<std::string> controllers;
  std::vector<std::string> overrides;  ///< --set, applied to every run after the controller's section
  /// "KEY=[V1, V2, ...]" (a YAML list); empty: compare.sweep, if any.
  std::string sweep;
  int jobs = 0;  ///< runs at a time; 0: one per core
  bool quiet = false;
  std::string self_exe;  ///< the lagrange binary, which runs each controller
};

/// One run of the comparison.
struct CompareRun {
  std::string type;                  ///< controller.type
  std::optional<std::string> value;  ///< the sweep value (YAML text); none: the nominal run
  std::vector<std::string> overrides;
  std::string dir;  ///< its output directory
};

/// What a comparison runs.
struct ComparisonPlan {
  /// The scenario with --set applied: its name, joints and reference are
  /// every nominal run's (a run differs from it in its controller section).
  config::Scenario base;
  std::string sweep_key;  ///< empty: no sweep
  std::vector<CompareRun> runs;
};

/// The runs the options ask for, each scenario read and checked (a bad
/// controller section, sweep key or value is named before anything runs).
/// @throws config::ConfigError naming what was wrong.
ComparisonPlan planComparison(const CompareOptions& options);

/// Runs the comparison and writes OUT/comparison.md, .csv and the plots.
/// Returns an exit code: 0 when every run completed (a controller that
/// diverged is a result, reported in the table, and exits 0 too), 2 for bad
/// input, 1 when a run could not be made.
int runComparison(const CompareOptions& options);

/// Declares `compare` and its options on the front end (tools/compare/compare_cli.cpp).
Subcommand addCompareCommand(CLI::App& app);

}  // namespace lagrange::tools
