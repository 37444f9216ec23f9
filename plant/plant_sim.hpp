#pragma once
/// @file
/// Simulation of an arm in one physics engine (plant/physics_engine.hpp:
/// ODE by default, MuJoCo, or a registered one): PlantSim validates the
/// setup, keeps the time, holds a torque profile over its parts, and stops a
/// failing run; the engine holds the world and steps it. Engines stay inside
/// the plant (RAII); callers see Eigen vectors only.
///
/// Flexible joints (model/flexible_joint.hpp): one rotor per joint, hinged to
/// the base with inertia J_i; the spring torque K_i (q2_i - q1_i) acts as
/// joint torque on joint i (+ on link i, - on link i-1) and opposite on rotor
/// i, and the input tau_i acts on rotor i.
///
/// No damping, friction or stops unless asked (JointPhysics): the paper's arm
/// is lossless. With them, the engine applies them inside its step
/// (implicitly on ODE; see plant/joint_effects.hpp) and dissipated() counts
/// the energy they took.

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "model/flexible_joint.hpp"
#include "plant/arm_world.hpp"
#include "plant/physics_engine.hpp"
#include "util/error.hpp"

namespace lagrange::plant {

/// Why the plant stopped a run: the simulation failed, or a limit the user set was crossed.
class PlantStopped : public lagrange::RuntimeFault {
 public:
  using lagrange::RuntimeFault::RuntimeFault;
};

/// How every PlantStopped message begins: what the launcher looks for in a
/// dead plant's log to call the run `diverged` (as in process) rather than
/// `failed`.
inline constexpr const char* kPlantStoppedMarks[] = {"plant: the simulation diverged ",
                                                     "plant: stopped at t = "};

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
///    MuJoCo integrates the angles themselves and needs no unwrapping, but a
///    step that turns a body by a quarter turn resolves nothing of the motion
///    either: the same limit holds on every engine. MuJoCo's own alarm (a
///    non-finite acceleration, after which it would reset the state) stops
///    the run as a non-finite state does.
///  - when a limit the user set (plant.max_rate) is crossed.
class PlantSim {
 public:
  /// The largest rotation of a body in one physics step the simulation follows [rad].
  static constexpr double kMaxTurnPerStep = M_PI / 2.0;

  /// @param arm the robot kind's builder (e.g. planarChainWorld(params)).
  /// @param physics_step the engine's step [s], > 0.
  /// @param flexible elastic joints with rotors; then `initial` needs motor_q, motor_qdot
  ///        and the torques of step() act on the rotors.
  /// @param max_rate a limit on any body's angular rate [rad/s] (plant.max_rate); none if unset.
  /// @param joints damping, friction and stops; none by default.
  /// @param engine the physics engine and its settings (plant.engine); ODE by default.
  /// @throws std::invalid_argument on a size mismatch, non-finite state, a bad step,
  ///         bad flexible parameters, bad joint physics, or an engine that cannot
  ///         simulate the arm (naming it).
  PlantSim(const ArmBuilder& arm, const PlantState& initial, double physics_step,
           std::optional<model::FlexibleParams> flexible = std::nullopt,
           std::optional<double> max_rate = std::nullopt, const JointPhysics& joints = {},
           const EngineChoice& engine = {});
  ~PlantSim();
  PlantSim(const PlantSim&) = delete;
  PlantSim& operator=(const PlantSim&) = delete;

  /// Advance by `substeps` physics steps with torques tau held constant (joint
  /// torques, or motor torques for flexible joints).
  /// @throws PlantStopped when the simulation fails (see the class comment),
  ///         before the engine itself would abort, or a body crosses max_rate.
  void step(const Eigen::VectorXd& tau, int substeps);
  /// Advance by `substeps` physics steps cut into tau.rows() equal parts, row
  /// s of tau (joint torques) held over part s: the actuator's output when it
  /// updates tau.rows() times a period. @throws std::invalid_argument unless
  /// tau.rows() divides substeps.
  void stepProfile(const Eigen::MatrixXd& tau, int substeps);

  PlantState state() const;
  PlantEnergy energy() const;
  /// Energy the damping and friction of the joints and rotors took since the
  /// start [J] (the engine's applied torques times the rates, step by step); 0
  /// without them. With it the balance holds without stops: E(t) - E(0) =
  /// work of the inputs - dissipated (an inelastic stop takes energy too).
  double dissipated() const;
  double time() const { return time_; }
  /// How far the joints have come apart in ODE's maximal coordinates [m]
  /// (ArmWorld::jointSeparation); 0 in an engine's generalized coordinates.
  double jointSeparation() const;
  /// The engine's name ("ODE", "MuJoCo").
  std::string engineName() const;
  double physicsStep() const { return physics_step_; }
  int dof() const { return dof_; }

 private:
  void checkBounded() const;

  int dof_;
  double physics_step_;
  double time_ = 0.0;
  std::unique_ptr<PhysicsEngine> engine_;
  std::optional<double> max_rate_;
};

}  // namespace lagrange::plant
