#include "tools/report/signal_range.hpp"

#include <algorithm>
#include <cmath>

#include "tools/report/csv_rows.hpp"

namespace lagrange::tools {

SignalRange signalRange(const std::string& path, const std::vector<std::string>& columns, double late_from) {
  SignalRange r;
  CsvRows rows(path);
  const int time = rows.column("sim_time");
  std::vector<int> index;
  std::vector<std::string> names;
  for (const std::string& c : columns)
    if (const int i = rows.column(c); i >= 0) index.push_back(i), names.push_back(c);
  if (time < 0 || index.empty()) return r;
  std::vector<double> row;
  while (rows.next(row)) {
    const double t = row[time];
    for (size_t k = 0; k < index.size(); ++k) {
      const double v = row[index[k]];
      if (!std::isfinite(v)) continue;
      if (r.empty || std::abs(v) > std::abs(r.peak)) {
        r.peak = v, r.peak_time = t, r.peak_column = names[k];
      }
      r.lo = r.empty ? v : std::min(r.lo, v);
      r.hi = r.empty ? v : std::max(r.hi, v);
      r.empty = false;
      if (t >= late_from) {
        r.late_lo = r.late_empty ? v : std::min(r.late_lo, v);
        r.late_hi = r.late_empty ? v : std::max(r.late_hi, v);
        r.late_empty = false;
      }
    }
  }
  return r;
}

std::pair<double, double> lateWindow(const SignalRange& r) {
  const double span = r.late_hi - r.late_lo;
  double margin = 0.05 * span;
  if (!(margin > 0)) margin = 0.05 * std::max(std::abs(r.late_lo), std::abs(r.late_hi));
  if (!(margin > 0)) margin = 1.0;
  return {r.late_lo - margin, r.late_hi + margin};
}

bool dominatedByStart(const SignalRange& r) {
  if (r.empty || r.late_empty) return false;
  const auto [lo, hi] = lateWindow(r);
  return r.hi - r.lo > 3.0 * (hi - lo);
}

}  // namespace lagrange::tools
