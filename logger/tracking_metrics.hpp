#pragma once
/// @file
/// Tracking metrics of a run, computed from the plant's true positions and
/// the reference (not from the controller's own view). Pure.

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "model/reference.hpp"

namespace lagrange::logger {

struct TrackingSummary {
  double tolerance = 0.0;
  double final_error = 0.0;  ///< ||q~(T)|| [rad]
  double max_error = 0.0;    ///< max_t ||q~(t)|| [rad]
  /// First sample time after which ||q~|| stays below the tolerance [s];
  /// empty if the last sample is not below it.
  std::optional<double> convergence_time;
  double rms_last_second = 0.0;  ///< RMS of ||q~|| over t >= T - 1 s [rad]
  double max_abs_torque = 0.0;   ///< max |tau_i| applied [N m]
  long long samples = 0;
  double sim_time = 0.0;  ///< time of the last sample [s]
};

class TrackingMetrics {
 public:
  TrackingMetrics(model::Reference reference, double tolerance);

  /// A plant sample. Ticks must increase; a repeated or older tick is ignored
  /// (returns false). Returns ||q~||.
  std::optional<double> addSample(long long tick, double t, const Eigen::VectorXd& q);
  void addTorque(const Eigen::VectorXd& tau);

  TrackingSummary summary() const;
  long long lastTick() const { return last_tick_; }
  double lastError() const { return errors_.empty() ? std::nan("") : errors_.back(); }
  double lastTime() const { return times_.empty() ? 0.0 : times_.back(); }

 private:
  model::Reference reference_;
  double tolerance_;
  long long last_tick_ = -1;
  std::vector<double> times_, errors_;
  double max_abs_torque_ = 0.0;
};

}  // namespace lagrange::logger
