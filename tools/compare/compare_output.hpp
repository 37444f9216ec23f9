#pragma once
/// @file
/// What `lagrange compare` writes once its runs are done (tools/compare/compare.hpp):
/// the table as Markdown and CSV, and the gnuplot pictures -- the tracking
/// error and the torques of the nominal runs overlaid, and the steady-state
/// error against a swept key, one curve per controller.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "tools/report/plots.hpp"

namespace lagrange::tools {

/// One run's numbers, from its summary.json (docs/summary.md).
struct RunNumbers {
  std::string type;
  std::optional<std::string> value;  ///< the sweep value; none: the nominal run
  std::string dir;
  std::string status;                      ///< completed, diverged, failed, or "failed (...)"
  std::string failure;                     ///< why a failed run failed (printed under the table)
  std::optional<double> convergence_time;  ///< tracking.convergence_time [s]
  double final_error = std::nan("");       ///< tracking.final_error [rad]
  double rms_last_second = std::nan("");   ///< tracking.rms_last_second [rad]
  double max_torque = std::nan("");        ///< torque.max_abs [N m]
  double total_variation = std::nan("");   ///< torque.total_variation [N m]
  double energy = std::nan("");            ///< torque.energy [N^2 m^2 s]
  std::string verdict;                     ///< verdict.tracking: met, NOT met, not judged (empty: none)
  std::string verdict_reason;              ///< verdict.reasons[0].text: the likeliest reason (empty: none)
};

struct ComparisonTables {
  std::string scenario;  ///< its name
  int dof = 0;
  std::string sweep_key;  ///< empty: no sweep
  std::vector<RunNumbers> runs;
};

/// Writes OUT/comparison.md and OUT/comparison.csv; returns the Markdown.
/// @throws RuntimeFault when a file cannot be written.
std::string writeComparison(const ComparisonTables& tables, const std::string& out_dir);

/// Writes OUT/compare.gp and draws error.png, torque.png and (with a sweep of
/// numbers) sweep.png. @throws PlotError when gnuplot is missing.
Plots drawComparisonPlots(const ComparisonTables& tables, const std::string& out_dir);

}  // namespace lagrange::tools
