#pragma once
/// @file
/// Actuator dynamics of eq. (600): per joint, a chain of m integrators
///   xi_1' = xi_2, ..., xi_m' = u,
/// whose first state xi_1 is the torque on the arm. Integrated exactly for a
/// zero-order-held u (the chain is linear and nilpotent, so the step is a
/// finite Taylor polynomial; no Euler):
///   xi_i(t + T) = sum_{j=i..m} xi_j(t) T^(j-i) / (j-i)! + u T^(m-i+1) / (m-i+1)!
/// Order m = 0 is the pass-through: the torque is u itself.
///
/// The torque the plant applies over a period is xi_1 at the start of the
/// period (held; for m = 0, the u of the period), optionally clipped to the
/// per-joint saturation limits. Clipping acts on the applied torque only; the
/// chain's state is not clipped. Pure: no I/O, no clock.

#include <Eigen/Dense>
#include <optional>

namespace lagrange::actuator {

struct ActuatorOutput {
  Eigen::VectorXd tau;                              ///< torque applied over the period [N m]
  Eigen::Array<bool, Eigen::Dynamic, 1> saturated;  ///< where tau was clipped
};

class IntegratorChain {
 public:
  static constexpr int kMaxOrder = 4;

  /// initial: m x dof matrix, row i-1 = xi_i(0) (empty for m = 0).
  /// @throws std::invalid_argument for m outside 0..4, size mismatches,
  ///         non-finite values or non-positive saturation limits.
  IntegratorChain(int dof, int order, std::optional<Eigen::VectorXd> saturation, Eigen::MatrixXd initial);

  /// The torque over the coming period (xi_1 now, or u for m = 0), then
  /// advances the chain by dt > 0 with u held.
  ActuatorOutput step(const Eigen::VectorXd& u, double dt);

  /// Advances the chain exactly by dt with u held, without producing a torque.
  void advance(const Eigen::VectorXd& u, double dt);

  const Eigen::MatrixXd& state() const { return xi_; }  ///< m x dof
  int order() const { return order_; }
  int dof() const { return dof_; }

 private:
  ActuatorOutput clip(const Eigen::VectorXd& tau) const;

  int dof_, order_;
  std::optional<Eigen::VectorXd> saturation_;
  Eigen::MatrixXd xi_;
};

}  // namespace lagrange::actuator
