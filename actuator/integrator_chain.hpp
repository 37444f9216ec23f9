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
/// The actuator updates its output `steps` times per control period T (its
/// rate is steps / T): the torque over step s, [t + s T/steps, t + (s+1) T/steps),
/// is xi_1 at the start of that step (held; for m = 0, the u of the period),
/// optionally clipped to the per-joint saturation limits. As steps grows the
/// plant sees the chain's continuous xi_1(t) more and more closely. Clipping
/// acts on the applied torque only; the chain's state is not clipped. Pure:
/// no I/O, no clock.

#include <Eigen/Dense>
#include <optional>

namespace lagrange::actuator {

struct ActuatorOutput {
  Eigen::MatrixXd tau;                              ///< steps x dof: row s held over step s [N m]
  Eigen::Array<bool, Eigen::Dynamic, 1> saturated;  ///< per joint: a row of tau was clipped
};

class IntegratorChain {
 public:
  static constexpr int kMaxOrder = 4;

  /// initial: m x dof matrix, row i-1 = xi_i(0) (empty for m = 0).
  /// @throws std::invalid_argument for m outside 0..4, size mismatches,
  ///         non-finite values or non-positive saturation limits.
  IntegratorChain(int dof, int order, std::optional<Eigen::VectorXd> saturation, Eigen::MatrixXd initial);

  /// The torque over the coming period of length dt > 0 in `steps` >= 1
  /// equal steps (xi_1 at the start of each, or u for m = 0), advancing the
  /// chain by dt with u held.
  ActuatorOutput step(const Eigen::VectorXd& u, double dt, int steps = 1);

  /// Advances the chain exactly by dt with u held, without producing a torque.
  void advance(const Eigen::VectorXd& u, double dt);

  const Eigen::MatrixXd& state() const { return xi_; }  ///< m x dof
  int order() const { return order_; }
  int dof() const { return dof_; }

 private:
  Eigen::VectorXd clip(const Eigen::VectorXd& tau) const;

  int dof_, order_;
  std::optional<Eigen::VectorXd> saturation_;
  Eigen::MatrixXd xi_;
};

}  // namespace lagrange::actuator
