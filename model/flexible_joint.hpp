#pragma once
/// @file
/// Flexible-joint arm, the model (595) of Spong / Burkov:
///   D(q1) q1'' + C(q1, q1') q1' + g(q1) = K (q2 - q1),
///   J q2'' + K (q2 - q1) = tau,
/// q1 the link (joint) angles of the rigid arm (any model::RobotModel), q2 the motor angles,
/// K = diag(stiffness) > 0, J = diag(rotor_inertia) > 0. No damping.
///
/// The mechanical system this describes exactly (and plant::PlantSim
/// simulates): every drive is base-mounted. Rotor i is a rigid body hinged to
/// the base, turning with q2_i, its stator reaction taken by the base; its
/// elastic transmission applies K_i (q2_i - q1_i) as joint torque on joint i
/// (+ on link i, - on link i-1) and the opposite torque on the rotor. The
/// rotors' masses therefore rest on the base and do not enter D(q1). A rotor
/// riding on link i-1 would add the gyroscopic coupling J_i phi_{i-1}' that
/// the simplified model (595) neglects; this design has none, so the analytic
/// model used by the controller is the plant, not an approximation of it.
///
/// Through xi_1 = K q2, xi_2 = K q2' the system is the chain (600) with m = 2,
/// u = K J^-1 (tau - K (q2 - q1)), and g(q1) replaced by g(q1) + K q1.
/// Pure: no I/O.

#include <Eigen/Dense>
#include <utility>

#include "model/robot_model.hpp"

namespace lagrange::model {

struct FlexibleParams {
  Eigen::VectorXd stiffness;      ///< K_i [N m / rad], > 0
  Eigen::VectorXd rotor_inertia;  ///< J_i [kg m^2], > 0
};

/// @throws std::invalid_argument unless both have `dof` positive finite entries.
void validateFlexible(const FlexibleParams& p, int dof);

/// The full state of the flexible arm.
struct FlexibleState {
  Eigen::VectorXd q1, v1;  ///< link angles [rad] and rates [rad/s]
  Eigen::VectorXd q2, v2;  ///< motor angles [rad] and rates [rad/s]
};

class FlexibleChain {
 public:
  /// @param links the rigid arm the elastic joints drive (without springs).
  /// @throws std::invalid_argument for bad parameters or no arm.
  FlexibleChain(RobotModelPtr links, FlexibleParams params);

  int dof() const { return links_->dof(); }
  const RobotModel& links() const { return *links_; }
  const FlexibleParams& params() const { return params_; }

  /// (q1'', q2'') of (595) under motor torques tau.
  std::pair<Eigen::VectorXd, Eigen::VectorXd> acceleration(const FlexibleState& x,
                                                           const Eigen::VectorXd& tau) const;

  /// Kinetic (links and rotors) + gravitational + spring energy [J].
  double energy(const FlexibleState& x) const;

 private:
  RobotModelPtr links_;
  FlexibleParams params_;
};

}  // namespace lagrange::model
