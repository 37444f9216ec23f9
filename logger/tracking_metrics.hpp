#pragma once
/// @file
/// Tracking metrics of a run, computed from the plant's true positions and
/// the reference (not from the controller's own view). Pure.

#include <Eigen/Dense>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "model/reference.hpp"

namespace lagrange::logger {

/// One error signal's history: ||e|| per sample, against a tolerance.
struct ErrorSummary {
  double tolerance = 0.0;
  double final_error = 0.0, max_error = 0.0;
  std::optional<double> convergence_time;  ///< first time after which ||e|| < tolerance to the end
};

/// A joint whose rate went past its limit (a URDF's <limit velocity>).
struct VelocityCrossing {
  std::string joint;
  double limit = 0.0;       ///< [rad/s]
  double largest = 0.0;     ///< the largest |q'| seen [rad/s]
  double first_time = 0.0;  ///< the first sample past the limit [s]
  long long samples = 0;    ///< samples past the limit
};

struct TrackingSummary {
  double tolerance = 0.0;
  double final_error = 0.0;     ///< ||q~(T)|| [rad]
  double max_error = 0.0;       ///< max_t ||q~(t)|| [rad]
  double max_error_time = 0.0;  ///< the first sample time at which max_error was reached [s]
  double initial_error = 0.0;   ///< ||q~|| of the first sample [rad]
  double first_time = 0.0;      ///< time of the first sample [s]
  /// First sample time after which ||q~|| stays below the tolerance [s];
  /// empty if the last sample is not below it.
  std::optional<double> convergence_time;
  double rms_last_second = 0.0;  ///< RMS of ||q~|| over t >= T - 1 s [rad]
  double max_abs_torque = 0.0;   ///< max |tau_i| applied [N m]
  /// With watchSaturation: the share of the ticks recorded whose torque put
  /// some joint at its limit (|tau_j| within 1e-9 relative of it) in any
  /// step of the period; empty without limits.
  std::optional<double> saturated_fraction;
  /// sum over joints of the total variation of the applied torque, step to
  /// step in tick order: sum_j sum_s |tau_j(s) - tau_j(s-1)| [N m] (chattering)
  double torque_total_variation = 0.0;
  /// integral of ||tau||^2 dt, each step held T / steps [N^2 m^2 s] (0 without a tick period)
  double control_energy = 0.0;
  long long samples = 0;
  double sim_time = 0.0;            ///< time of the last sample [s]
  std::vector<ErrorSummary> chain;  ///< ||xit_i|| per stage i (cascaded controller)
  /// With watchVelocities: the joints that went past their limits (maybe none).
  std::optional<std::vector<VelocityCrossing>> velocity_crossings;
};

class TrackingMetrics {
 public:
  /// tick_period [s]: the time each ACTUATOR_STATE's torque profile spans
  /// (for the control energy; 0: not computed).
  TrackingMetrics(model::Reference reference, double tolerance, double xi_tolerance = 1e-2,
                  double tick_period = 0.0);

  /// A plant sample, in any order (a re-sent one may come late); a tick
  /// already recorded is ignored (returns nothing). Returns ||q~||.
  /// With `qdot` (the true rates) and watchVelocities, the rates are checked too.
  std::optional<double> addSample(long long tick, double t, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& qdot = Eigen::VectorXd());
  /// Watches each joint's |q'| against limits(i) (+inf: none) [rad/s].
  void watchVelocities(std::vector<std::string> joints, Eigen::VectorXd limits);
  /// Counts the ticks whose applied torque sat at a limit (actuator.saturation) [N m].
  void watchSaturation(Eigen::VectorXd limits) { saturation_ = std::move(limits); }
  /// The torque profile applied after tick `tick` (rows: steps of the
  /// period); a tick already recorded is ignored.
  void addTorque(long long tick, const Eigen::MatrixXd& tau);

  /// The cascaded controller's chain errors xit_i at a tick (rows = stages),
  /// judged against xi_tolerance. Repeated or older ticks are ignored.
  void addChainErrors(long long tick, double t, const std::vector<std::vector<double>>& xi_error);

  TrackingSummary summary() const;
  /// The run's time of a tick [s]: tick x tick_period, as the plant computes it.
  double timeOf(long long tick) const { return static_cast<double>(tick) * tick_period_; }
  /// The last tick up to which every sample is recorded (-1: not tick 0 yet).
  long long lastTick() const { return contiguous_tick_; }
  /// The newest tick recorded (-1: none).
  long long newestTick() const { return samples_.empty() ? -1 : samples_.rbegin()->first; }
  /// ||q~|| and time of the newest sample.
  double lastError() const { return samples_.empty() ? std::nan("") : samples_.rbegin()->second.error; }
  double lastTime() const { return samples_.empty() ? 0.0 : samples_.rbegin()->second.t; }

 private:
  model::Reference reference_;
  double tolerance_;
  struct Sample {
    double t, error;
  };
  std::map<long long, Sample> samples_;                          ///< by tick
  std::optional<std::vector<VelocityCrossing>> velocity_watch_;  ///< limits, and what crossed them
  Eigen::VectorXd velocity_limits_;
  long long contiguous_tick_ = -1;
  double tick_period_;
  std::map<long long, Eigen::MatrixXd> torques_;  ///< by tick
  std::optional<Eigen::VectorXd> saturation_;     ///< per-joint |tau| limits
  double xi_tolerance_;
  long long last_chain_tick_ = -1;
  std::vector<double> chain_times_;
  std::vector<std::vector<double>> chain_errors_;  ///< [stage][sample]
};

}  // namespace lagrange::logger
