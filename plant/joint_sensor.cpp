#include "plant/joint_sensor.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace lagrange::plant {

JointSensor::JointSensor(int joints)
    : JointSensor(joints, {Eigen::VectorXd::Zero(joints), Eigen::VectorXd::Zero(joints), 0, 1, {}}) {}

JointSensor::JointSensor(int joints, JointSensorParams params)
    : params_(std::move(params)), rng_(params_.seed) {
  for (const Eigen::VectorXd* v : {&params_.counts_per_revolution, &params_.noise_sigma})
    if (v->size() != joints || !v->allFinite() || (v->array() < 0.0).any())
      throw std::invalid_argument("JointSensor: counts per revolution and noise sigma must have " +
                                  std::to_string(joints) + " finite entries >= 0");
  if (params_.delay < 0) throw std::invalid_argument("JointSensor: the delay must be >= 0 samples");
  ideal_ = params_.delay == 0 && (params_.counts_per_revolution.array() == 0.0).all() &&
           (params_.noise_sigma.array() == 0.0).all() && params_.effects.empty();
}

Eigen::VectorXd JointSensor::measure(const Eigen::VectorXd& q_true) {
  if (ideal_) return q_true;
  if (history_.empty())
    history_.assign(static_cast<size_t>(params_.delay) + 1, q_true);  // held before tick d
  history_.push_back(q_true);
  history_.pop_front();
  Eigen::VectorXd q = history_.front();
  for (const std::unique_ptr<SensorEffect>& effect : params_.effects) {
    q = effect->apply(q);
    if (q.size() != q_true.size())
      throw std::logic_error("JointSensor: a sensor effect returned " + std::to_string(q.size()) +
                             " values for " + std::to_string(q_true.size()) + " joints");
  }
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    // One draw per joint with noise, every tick: the sequence does not depend on the angles.
    if (params_.noise_sigma(i) > 0.0) q(i) += params_.noise_sigma(i) * normal_(rng_);
    if (params_.counts_per_revolution(i) > 0.0) {
      const double step = 2.0 * M_PI / params_.counts_per_revolution(i);
      q(i) = std::floor(q(i) / step) * step;
    }
  }
  return q;
}

}  // namespace lagrange::plant
