#pragma once
/// @file
/// The range of some columns of a report CSV over the whole run and after a
/// time, so a plot can tell whether its start-up transient (the torque a
/// large initial error asks for at t = 0) would flatten everything after it,
/// and clip the range when it would -- saying so, with the peak it cut.

#include <string>
#include <vector>

namespace lagrange::tools {

struct SignalRange {
  bool empty = true;                    ///< no finite value in the columns
  double lo = 0.0, hi = 0.0;            ///< over the whole run
  bool late_empty = true;               ///< no finite value at t >= late_from
  double late_lo = 0.0, late_hi = 0.0;  ///< over t >= late_from
  double peak = 0.0;                    ///< the value of largest magnitude (signed)
  double peak_time = 0.0;               ///< when it was reached [s]
  std::string peak_column;              ///< in which column
};

/// Over `columns` of the CSV at `path` (time in its sim_time column).
SignalRange signalRange(const std::string& path, const std::vector<std::string>& columns, double late_from);

/// The y range to draw after the transient: the later range with a margin of
/// 5 % of its span (of its magnitude, or 1, when the later signal is constant).
std::pair<double, double> lateWindow(const SignalRange& r);

/// Whether drawing the whole range would flatten the later signal: the whole
/// span is more than three times the later window's.
bool dominatedByStart(const SignalRange& r);

}  // namespace lagrange::tools
