#pragma once
/// @file
/// The physics-engine seam: what plant::PlantSim needs of an engine, and the
/// one place an engine is picked by name (plant.engine). PlantSim validates
/// the setup, keeps the time, and stops a failing run; the engine holds its
/// world (ODE's bodies and joints, MuJoCo's model and data), applies the
/// inputs, steps, and reads the state back. Built in: "ode"
/// (plant/ode_engine.hpp, maximal coordinates, the design's engine) and
/// "mujoco" (plant/mujoco/, generalized coordinates). A further engine is a
/// folder and one registration:
///
///     const bool registered = lagrange::plant::registerPhysicsEngine(
///         "my_engine", [](const EngineSetup& s) { return std::make_unique<MyEngine>(s); });
///
/// `plant: {engine: my_engine}` then picks it in every wiring and in replay
/// (tests/unit/physics_engine_test.cpp registers one that exists only there).

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/flexible_joint.hpp"
#include "plant/arm_world.hpp"

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
  bool any() const { return damping.size() > 0 || friction.size() > 0 || lower.size() > 0; }
};

struct PlantEnergy {
  double kinetic = 0.0;    ///< [J], links and rotors
  double potential = 0.0;  ///< [J], the links' heights, plus the springs' for flexible joints
  double total() const { return kinetic + potential; }
};

/// MuJoCo's integrators (plant.mujoco_integrator): mjINT_RK4, mjINT_IMPLICIT, mjINT_EULER.
enum class MujocoIntegrator { kRk4, kImplicit, kEuler };

/// Which engine, and its own settings (plant.engine, plant.mujoco_integrator).
struct EngineChoice {
  std::string key = "ode";
  MujocoIntegrator mujoco_integrator = MujocoIntegrator::kRk4;
};

/// What an engine is built from, validated by PlantSim before it is passed on.
struct EngineSetup {
  ArmBuilder arm;
  PlantState initial;
  double physics_step = 0.0;
  std::optional<model::FlexibleParams> flexible;  ///< rotors hinged to the base, springs to the links
  JointPhysics joints;
  EngineChoice choice;
};

/// One simulated arm in one engine. Flexible joints: the input torques act on
/// the rotors and the springs K_i (q2_i - q1_i) on the links, as
/// plant/plant_sim.hpp describes; else they are the joint torques.
class PhysicsEngine {
 public:
  virtual ~PhysicsEngine() = default;
  /// One physics step of EngineSetup::physics_step with `input` held.
  virtual void step(const Eigen::VectorXd& input) = 0;
  /// The joint (and motor) angles, continuous over turns, and rates.
  virtual PlantState state() const = 0;
  virtual PlantEnergy energy() const = 0;
  /// Energy the joints' and rotors' damping and friction took since the start [J].
  virtual double dissipated() const = 0;
  /// The fastest angular rate of any link or rotor [rad/s].
  virtual double fastestBodyRate() const = 0;
  /// Empty while the engine's whole state is finite and its last step
  /// sound; else why not, for the message that stops the run.
  virtual std::string unsound() const = 0;
  /// How far the joints have come apart [m]: 0 in generalized coordinates.
  virtual double jointSeparation() const = 0;
  /// The engine's name in messages ("ODE", "MuJoCo").
  virtual std::string name() const = 0;
};

/// Refuses joint physics no engine can apply: a per-joint vector of another
/// size than `dof`, a negative or non-finite loss, crossed or NaN stops,
/// rotor losses without flexible joints. @throws std::invalid_argument naming it.
void checkJointPhysics(const JointPhysics& joints, int dof, bool flexible);

using EngineFactory = std::function<std::unique_ptr<PhysicsEngine>(const EngineSetup&)>;

/// Adds an engine's factory under `key`; plant::registerPhysicsEngine
/// (plant/robot_kinds.hpp) calls it and tells config the key. @throws
/// std::logic_error for a key taken or a factory missing.
void addPhysicsEngineFactory(const std::string& key, EngineFactory factory);

/// The engine setup.choice.key names, built from `setup`. @throws std::invalid_argument
/// for a key no engine has, or a setup the engine cannot simulate (naming
/// the key and the engine).
std::unique_ptr<PhysicsEngine> makePhysicsEngine(const EngineSetup& setup);

/// The keys of the engines this program has, built-in first.
std::vector<std::string> physicsEngineKeys();

}  // namespace lagrange::plant
