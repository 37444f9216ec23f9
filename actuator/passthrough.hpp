#pragma once
/// @file
/// Actuator of order m = 0: the commanded torque passes through to the plant,
/// optionally clipped per joint to [-limit, +limit]. Integrator chains
/// (m >= 1) slot in beside it with the same step() shape. Pure.

#include <Eigen/Dense>
#include <optional>

namespace lagrange::actuator {

struct ActuatorOutput {
  Eigen::VectorXd tau;                              ///< torque applied [N m]
  Eigen::Array<bool, Eigen::Dynamic, 1> saturated;  ///< where tau was clipped
};

class PassthroughActuator {
 public:
  /// saturation: per-joint positive limits [N m], or none.
  /// @throws std::invalid_argument on a size mismatch or a non-positive limit.
  PassthroughActuator(int dof, std::optional<Eigen::VectorXd> saturation);

  /// Torque for command u over the next period (held constant).
  ActuatorOutput step(const Eigen::VectorXd& u) const;

  int dof() const { return dof_; }

 private:
  int dof_;
  std::optional<Eigen::VectorXd> saturation_;
};

}  // namespace lagrange::actuator
