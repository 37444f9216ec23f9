#pragma once
/// @file
/// ODE simulation of an arm: the world of one robot kind's builder
/// (plant/arm_world.hpp; the planar chain's in plant/planar_chain_world.hpp),
/// stepped by dWorldStep (the accurate stepper), no damping and no
/// angular-speed clamp. ODE stays inside the plant (RAII); callers see Eigen
/// vectors only.
///
/// Torques are re-applied before every physics sub-step (ODE clears its force
/// accumulators after each step): joint torque tau_i acts +tau_i on link i and
/// -tau_i on its parent. Joint angles, which the bodies show modulo 2 pi, are
/// kept continuous (multi-turn): each sub-step the wrapped angle is unwrapped
/// towards the angle predicted from the joint rate, so turns are counted
/// correctly as long as the rate is below pi / physics_step.
///
/// Flexible joints (model/flexible_joint.hpp): one more body per joint, the
/// rotor, hinged to the base on the z axis with inertia J_i about it. Each
/// sub-step the spring torque K_i (q2_i - q1_i) acts as joint torque on joint
/// i (+ on link i, - on link i-1) and opposite on rotor i, and the input tau_i
/// acts on rotor i; the stator reaction goes to the base.
///
/// No damping, friction or stops unless asked (JointPhysics): the paper's arm
/// is lossless. With them, ODE applies them inside its step (implicitly; see
/// plant/joint_effects.hpp) and dissipated() counts the energy they took.

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "model/flexible_joint.hpp"
#include "plant/arm_world.hpp"
#include "util/error.hpp"

namespace lagrange::plant {

struct PlantState {
  Eigen::VectorXd q;             ///< joint (link) angles [rad], continuous
  Eigen::VectorXd qdot;          ///< joint rates [rad/s]
  Eigen::VectorXd motor_q{};     ///< flexible joints: motor angles q2 [rad], continuous; else empty
  Eigen::VectorXd motor_qdot{};  ///< flexible joints: motor rates q2' [rad/s]; else empty
};

/// Damping, friction and hard stops of a real arm (plant/joint_effects.hpp's
/// rules; empty vectors: none).
struct JointPhysics {
  Eigen::VectorXd damping;         ///< the arm's joints: D_i [N m s/rad]
  Eigen::VectorXd friction;        ///< the arm's joints: Coulomb F_i [N m]
  Eigen::VectorXd rotor_damping;   ///< flexible joints' rotors [N m s/rad]
  Eigen::VectorXd rotor_friction;  ///< flexible joints' rotors [N m]
  Eigen::VectorXd lower, upper;    ///< the arm's joints' hard stops [rad]; +-inf: none that side
};

struct PlantEnergy {
  double kinetic = 0.0;    ///< [J], from the bodies' velocities
  double potential = 0.0;  ///< [J], from the bodies' heights, plus the springs' for flexible joints
  double total() const { return kinetic + potential; }
};

/// Why the plant stopped a run: the simulation failed, or a limit the user set was crossed.
class PlantStopped : public lagrange::RuntimeFault {
 public:
  using lagrange::RuntimeFault::RuntimeFault;
};

/// No artificial limit on the state: the global results are about large
/// errors, and converging runs pass through fast motion. A run is stopped only
///  - when the simulation fails: a non-finite body state, or a body turning by
///    more than kMaxTurnPerStep = pi/2 in one physics step. Past that, ODE's
///    first-order rotation update is meaningless and the joint angles can no
///    longer be unwrapped (two bodies each below pi/2 per step keep their
///    relative angle below pi per step, which the unwrapping needs); a state
///    still growing then reaches inf within steps and ODE aborts normalising a
///    quaternion. The limit in rad/s is kMaxTurnPerStep / physics_step
///    (62 832 rad/s at the shipped 2.5e-5 s), and shrinks with a smaller step.
///  - when a limit the user set (plant.max_rate) is crossed.
class PlantSim {
 public:
  /// The largest rotation of a body in one physics step the simulation follows [rad].
  static constexpr double kMaxTurnPerStep = M_PI / 2.0;

  /// @param arm the robot kind's builder (e.g. planarChainWorld(params)).
  /// @param physics_step ODE step [s], > 0.
  /// @param flexible elastic joints with rotors; then `initial` needs motor_q, motor_qdot
  ///        and the torques of step() act on the rotors.
  /// @param max_rate a limit on any body's angular rate [rad/s] (plant.max_rate); none if unset.
  /// @param joints damping, friction and stops; none by default.
  /// @throws std::invalid_argument on a size mismatch, non-finite state, a bad step,
  ///         bad flexible parameters or bad joint physics.
  PlantSim(const ArmBuilder& arm, const PlantState& initial, double physics_step,
           std::optional<model::FlexibleParams> flexible = std::nullopt,
           std::optional<double> max_rate = std::nullopt, const JointPhysics& joints = {});
  ~PlantSim();
  PlantSim(const PlantSim&) = delete;
  PlantSim& operator=(const PlantSim&) = delete;

  /// Advance by `substeps` physics steps with torques tau held constant (joint
  /// torques, or motor torques for flexible joints).
  /// @throws PlantStopped when the simulation fails (see the class comment),
  ///         before ODE itself would abort, or a body crosses max_rate.
  void step(const Eigen::VectorXd& tau, int substeps);
  /// Advance by `substeps` physics steps cut into tau.rows() equal parts, row
  /// s of tau (joint torques) held over part s: the actuator's output when it
  /// updates tau.rows() times a period. @throws std::invalid_argument unless
  /// tau.rows() divides substeps.
  void stepProfile(const Eigen::MatrixXd& tau, int substeps);

  PlantState state() const;
  PlantEnergy energy() const;
  /// Energy the damping and friction of the joints and rotors took since the
  /// start [J] (ODE's applied torques times the rates, step by step); 0
  /// without them. With it the balance holds without stops: E(t) - E(0) =
  /// work of the inputs - dissipated (an inelastic stop takes energy too).
  double dissipated() const;
  double time() const { return time_; }
  /// How far the joints have come apart in ODE's maximal coordinates [m] (ArmWorld::jointSeparation).
  double jointSeparation() const;
  double physicsStep() const { return physics_step_; }
  int dof() const { return dof_; }

 private:
  struct Ode;
  void updateJointAngles();
  void updateMotorAngles();
  Eigen::VectorXd rotorRates() const;
  void checkBounded() const;
  bool flexible() const { return flexible_.has_value(); }

  int dof_;
  double physics_step_;
  double time_ = 0.0;
  std::unique_ptr<Ode> ode_;
  Eigen::VectorXd q_;        ///< continuous joint angles
  Eigen::VectorXd motor_q_;  ///< continuous motor angles (flexible joints)
  std::optional<model::FlexibleParams> flexible_;
  std::optional<double> max_rate_;
};

}  // namespace lagrange::plant
