#pragma once
/// @file
/// A sensor per joint in the plant's measurement path: what PLANT_POSITION
/// (joint angles), PLANT_RATE (a tachometer's joint rates) and PLANT_MOTOR
/// (motor angles) carry instead of the true values (which stay in
/// PLANT_TRUTH). Per joint, in this order:
///   delay:        the reading of tick k is of the value at tick k - d (whole
///                 samples; before tick d, the value at tick 0);
///   effects:      what registered sensor models do to the value
///                 (plant/sensor_models.hpp), each in turn;
///   noise:        plus a Gaussian draw of standard deviation sigma [rad, rad/s];
///   quantisation: an encoder of N counts per revolution reports
///                 floor(angle / delta) delta, delta = 2 pi / N -- the count
///                 below the angle, as an incremental encoder counts edges
///                 (a bias of half a count on average; 0 counts: none).
/// Seeded: the same seed gives the same draws in every wiring (lockstep,
/// realtime, in-process) and in replay. Call measure() once per tick, in tick
/// order. An ideal sensor returns the true values untouched (the same doubles).
/// Pure: no I/O.

#include <Eigen/Dense>
#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <vector>

namespace lagrange::plant {

/// What a sensor model does to one sensor's value, tick by tick
/// (plant/sensor_models.hpp makes them from the scenario).
class SensorEffect {
 public:
  virtual ~SensorEffect() = default;
  /// The value read instead of `value` (one entry per joint). Called once
  /// per tick, in tick order; the same calls give the same results.
  virtual Eigen::VectorXd apply(const Eigen::VectorXd& value) = 0;
};

struct JointSensorParams {
  Eigen::VectorXd counts_per_revolution;  ///< per joint; 0: not quantised
  Eigen::VectorXd noise_sigma;            ///< per joint [rad]; 0: no noise
  int delay = 0;                          ///< whole samples
  uint64_t seed = 1;
  std::vector<std::unique_ptr<SensorEffect>> effects;  ///< in order; none: the built-in steps only
};

class JointSensor {
 public:
  /// An ideal sensor of `joints` joints.
  explicit JointSensor(int joints);
  /// @throws std::invalid_argument unless both vectors have `joints` entries
  ///         >= 0 (finite) and delay >= 0.
  JointSensor(int joints, JointSensorParams params);

  /// The reading of the next tick from its true angles.
  Eigen::VectorXd measure(const Eigen::VectorXd& q_true);
  bool ideal() const { return ideal_; }

 private:
  JointSensorParams params_;
  bool ideal_ = true;
  std::deque<Eigen::VectorXd> history_;  ///< the last delay + 1 true readings, oldest first
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace lagrange::plant
