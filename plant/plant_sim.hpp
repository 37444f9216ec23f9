#pragma once
/// @file
/// ODE simulation of the planar chain of model::PlanarChain: one rigid body per
/// link, hinge joints about the z axis, gravity -g along y, dWorldStep (the
/// accurate stepper), no damping and no angular-speed clamp. ODE stays inside
/// this class (RAII); callers see Eigen vectors only.
///
/// Torques are re-applied before every physics sub-step (ODE clears its force
/// accumulators after each step): joint torque tau_i acts +tau_i on link i and
/// -tau_i on link i-1. Joint angles are reconstructed from the bodies' absolute
/// orientations and kept continuous (multi-turn): each sub-step the wrapped
/// angle is unwrapped towards the angle predicted from the joint rate, so
/// turns are counted correctly as long as the rate is below pi / physics_step.

#include <Eigen/Dense>
#include <memory>

#include "model/planar_chain.hpp"

namespace lagrange::plant {

struct PlantState {
  Eigen::VectorXd q;     ///< joint angles [rad], continuous
  Eigen::VectorXd qdot;  ///< joint rates [rad/s]
};

struct PlantEnergy {
  double kinetic = 0.0;    ///< [J], from the bodies' velocities
  double potential = 0.0;  ///< [J], from the bodies' heights
  double total() const { return kinetic + potential; }
};

class PlantSim {
 public:
  /// @param physics_step ODE step [s], > 0.
  /// @throws std::invalid_argument on a size mismatch, non-finite state or a bad step.
  PlantSim(const model::ChainParams& params, const PlantState& initial, double physics_step);
  ~PlantSim();
  PlantSim(const PlantSim&) = delete;
  PlantSim& operator=(const PlantSim&) = delete;

  /// Advance by `substeps` physics steps with joint torques tau held constant.
  void step(const Eigen::VectorXd& tau, int substeps);
  /// Advance by `substeps` physics steps cut into tau.rows() equal parts, row
  /// s of tau (joint torques) held over part s: the actuator's output when it
  /// updates tau.rows() times a period. @throws std::invalid_argument unless
  /// tau.rows() divides substeps.
  void stepProfile(const Eigen::MatrixXd& tau, int substeps);

  PlantState state() const;
  PlantEnergy energy() const;
  double time() const { return time_; }
  double physicsStep() const { return physics_step_; }
  int dof() const { return dof_; }

 private:
  struct Ode;
  void updateJointAngles();

  int dof_;
  double physics_step_;
  double time_ = 0.0;
  double gravity_;
  std::unique_ptr<Ode> ode_;
  Eigen::VectorXd q_;  ///< continuous joint angles
};

}  // namespace lagrange::plant
