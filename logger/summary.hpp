#pragma once
/// @file
/// summary.json: the numbers of a run (every key in docs/summary.md).

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "lagrange/status_t.hpp"
#include "logger/tracking_metrics.hpp"

namespace lagrange::logger {

struct RunFacts {
  std::string status;  ///< "completed" or "interrupted"
  double wall_time = 0.0;
  std::string log_path;
  long long log_events = 0;
  std::map<std::string, lagrange::status_t> final_status;  ///< by process name
  int64_t run_id = 0;                                      ///< the run's identity (header.run_id)
  int nice = 0;                                            ///< the logger's nice value (lockstep.logger_nice)
  /// Per per-tick channel: ticks up to the newest sample with no intact message in the log.
  std::map<std::string, long long> missing_ticks;
  /// Per channel: messages of the run's processes the log lacks (logger::RecordGaps).
  std::map<std::string, long long> missing_records;
  /// Per channel and reason: authenticated datagrams the logger did not
  /// record because no process of the run would accept their header
  /// (logger/record_filter.hpp).
  std::map<std::string, std::map<std::string, long long>> not_recorded;
  /// How long the controller and the actuator took to answer (logger/answer_times.hpp).
  nlohmann::json answers;
  /// Realtime, external controller: its loop as its commands' arrivals show
  /// it (logger/arrival_timing.hpp); null otherwise.
  nlohmann::json external_controller_loop;
};

/// Makes `metrics` watch the joints' rates against the URDF's <limit
/// velocity> when the arm has any (summary.json limits.velocity), and the
/// applied torque against actuator.saturation when set
/// (torque.saturated_fraction).
void watchLimits(TrackingMetrics& metrics, const config::Scenario& scenario);

nlohmann::json makeSummary(const config::Scenario& scenario, const TrackingSummary& tracking,
                           const controller::GainReport& gains, const RunFacts& facts);

}  // namespace lagrange::logger
