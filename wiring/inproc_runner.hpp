#pragma once
/// @file
/// The in-process wiring (`mode: inproc`): the same plant, actuator,
/// controller and metric cores as the LCM processes, called directly in one
/// process in the lockstep order, with no LCM traffic. It writes the same
/// run.lcm (the messages the processes would have published) and
/// summary.json, and its trajectories are bit-identical to lockstep runs.

#include <Eigen/Dense>
#include <string>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "logger/tracking_metrics.hpp"

namespace lagrange::logger {
class EventLog;
}

namespace lagrange::wiring {

class ProgressDisplay;

/// How an in-process simulation ended.
struct InProcessOutcome {
  int exit_code = 0;   ///< 0 completed (or cut), 1 the plant stopped the run, 130 interrupted
  std::string status;  ///< summary.json's: completed, diverged or interrupted; "cut": a TickWatch ended it
  std::string stop_message;  ///< why the plant stopped the run (empty otherwise)
  logger::TrackingSummary tracking;
  double wall_time = 0.0;  ///< [s]
};

/// Sees each tick of an in-process run once its torque is known, and may end
/// the run there: lagrange tune stops a candidate's run as soon as it can no
/// longer beat the best (tools/tune/tune_evaluate.hpp).
class TickWatch {
 public:
  virtual ~TickWatch() = default;
  /// Tick `tick`: `error` is the metric's ||q~|| of its sample, `tau` the
  /// torque profile applied after it (rows: steps of the period). false:
  /// end the run here, before the physics steps past the tick (status "cut").
  virtual bool keepGoing(long long tick, double error, const Eigen::MatrixXd& tau) = 0;
};

/// The in-process loop itself: every message goes to `log` when one is given
/// (none: nothing is written, as for a sweep's runs, which keep numbers only).
/// `progress`, `stop_requested` and `watch` may be null.
InProcessOutcome simulateInProcess(const config::Scenario& scenario, logger::EventLog* log,
                                   ProgressDisplay* progress, bool (*stop_requested)(),
                                   TickWatch* watch = nullptr);

/// Runs the scenario; writes run.lcm and summary.json into out_dir.
/// Returns 0, or 130 when stop_requested() became true midway.
/// `gains`: the scenario's gain report, as the launcher already computed it
/// (the sampled-data check is not cheap), written into summary.json.
int runInProcess(const config::Scenario& scenario, const controller::GainReport& gains,
                 const std::string& out_dir, ProgressDisplay& progress, bool (*stop_requested)());

}  // namespace lagrange::wiring
