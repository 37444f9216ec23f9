#include "tools/report/tracking_table.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "logger/tracking_metrics.hpp"
#include "model/reference.hpp"
#include "tools/report/csv_rows.hpp"
#include "transport/channels.hpp"
#include "util/number_text.hpp"
#include "util/output_stream.hpp"

namespace lagrange::tools {

TrackingTable exportTracking(const config::Scenario& s, const std::string& out_dir) {
  namespace fs = std::filesystem;
  TrackingTable table;
  CsvRows truth((fs::path(out_dir) / (std::string(transport::kPlantTruth) + ".csv")).string());
  const int n = s.dof();
  const int tick = truth.column("tick"), time = truth.column("sim_time");
  std::vector<int> q(n), qdot(n);
  for (int j = 0; j < n; ++j) {
    q[j] = truth.column("q[" + std::to_string(j + 1) + "]");
    qdot[j] = truth.column("qdot[" + std::to_string(j + 1) + "]");
    if (q[j] < 0 || qdot[j] < 0) return table;  // not this scenario's arm: nothing derived
  }
  if (tick < 0 || time < 0) return table;

  const model::Reference reference(s.reference);
  logger::TrackingMetrics metrics(reference, s.metrics.tolerance);
  util::OutputStream out((fs::path(out_dir) / (std::string(kTrackingChannel) + ".csv")).string());
  out << "tick,sim_time,q_error_norm";
  for (const char* field : {"q_error", "qdot_desired", "qdot_error"})
    for (int j = 1; j <= n; ++j) out << "," << field << "[" << j << "]";
  out << "\n";
  std::vector<double> row;
  Eigen::VectorXd position(n), rate(n);
  try {
    while (truth.next(row)) {
      // A row a damaged log left without a tick or time is not a sample, nor
      // one off the run's clock: the time is the tick's (tick / publish_rate),
      // never a sender's stamp, and the ticks are the scenario's.
      if (!std::isfinite(row[time]) || !std::isfinite(row[tick]) || row[tick] < 0 ||
          row[tick] > static_cast<double>(s.lastTick())) {
        ++table.skipped;
        continue;
      }
      const double t = row[tick] * s.tickPeriod();
      if (!(std::abs(row[time] - t) <= 1e-6 * s.tickPeriod())) {
        ++table.skipped;
        continue;
      }
      for (int j = 0; j < n; ++j) position(j) = row[q[j]], rate(j) = row[qdot[j]];
      const model::ReferenceSample desired = reference.evaluate(t, 1);
      const Eigen::VectorXd error = position - desired.q(), rate_error = rate - desired.qd();
      metrics.addSample(static_cast<long long>(row[tick]), t, position);
      out << util::exactText(row[tick]) << "," << util::exactText(t) << "," << util::exactText(error.norm());
      for (const Eigen::VectorXd* v : {&error, &desired.qd(), &rate_error})
        for (int j = 0; j < n; ++j) out << "," << util::exactText((*v)(j));
      out << "\n";
      ++table.rows;
      table.end_time = t;
    }
  } catch (const std::invalid_argument& e) {
    // A time the reference does not reach (a free_motion reference past its
    // horizon, in a log whose times were tampered with): no table, said why.
    out.close();
    fs::remove(out.path());
    TrackingTable none;
    none.problem = std::string("TRACKING.csv not derived: ") + e.what();
    return none;
  }
  out.close();
  table.convergence_time = metrics.summary().convergence_time;
  return table;
}

}  // namespace lagrange::tools
