#pragma once
/// @file
/// The plant's seam for robot kinds: what one kind puts into the ODE world
/// (its link bodies and joints, placed at the initial state, and the direction
/// of gravity) and how ODE's engine reads joint angles, rates and energy back
/// and applies joint torques; and the same arm as bodies at q = 0 for every
/// other engine (plant/physics_engine.hpp). The engines own their worlds,
/// step them and add the flexible joints' rotors; they know no kind. One builder per kind
/// (plant/planar_chain_world.hpp).

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

// ODE's world and joints (ODE's dWorldID is dxWorld*, dJointID dxJoint*), declared rather than included so
// that the plant's users do not compile against ODE: only plant/ links it.
struct dxWorld;
struct dxJoint;

namespace lagrange::plant {

/// A kind's arm inside an ODE world. Its bodies and joints belong to the world
/// (destroyed with it); the object only reads and pushes them.
class ArmWorld {
 public:
  virtual ~ArmWorld() = default;

  virtual int dof() const = 0;
  /// Adds joint torque tau_i to the bodies' accumulators: + on link i, - on its
  /// parent (nothing on the fixed base). Called before every physics step.
  virtual void addJointTorques(const Eigen::VectorXd& tau) = 0;
  /// The joint angles as the bodies show them, each known only modulo 2 pi [rad].
  virtual Eigen::VectorXd wrappedJointAngles() const = 0;
  /// The joint rates [rad/s].
  virtual Eigen::VectorXd jointRates() const = 0;
  /// The fastest angular rate of any link body [rad/s] (PlantSim's step limit).
  virtual double fastestBodyRate() const = 0;
  /// Whether every body's position, orientation and velocities are finite.
  virtual bool finite() const = 0;
  /// The largest distance between the two bodies' points of any joint [m]:
  /// how far ODE's maximal coordinates have let the chain come apart.
  virtual double jointSeparation() const = 0;
  /// Joint i's hinge, attached (link i, its parent or the world): where the
  /// plant adds damping, friction and stops (plant/joint_effects.hpp).
  virtual std::vector<dxJoint*> hinges() const = 0;
  /// Kinetic and potential energy of the links, from the bodies' states [J].
  virtual double kineticEnergy() const = 0;
  virtual double potentialEnergy() const = 0;
};

/// One body of a serial arm as it stands at q = 0, in the base frame.
struct ChainBody {
  Eigen::Vector3d joint_anchor;  ///< a point on its joint's axis [m]
  Eigen::Vector3d joint_axis;    ///< unit vector, positive rotation by the right-hand rule
  double mass = 0.0;             ///< [kg]
  Eigen::Vector3d com;           ///< centre of mass [m]
  Eigen::Matrix3d inertia;       ///< about the centre of mass, base-frame axes [kg m^2]
};

/// The arm as an engine that builds its own model reads it (MuJoCo): its
/// bodies base to tip, each moved by its joint and every joint before it, and
/// gravity as a vector in the base frame [m/s^2].
struct ArmBodies {
  std::vector<ChainBody> bodies;
  Eigen::Vector3d gravity;
};

/// How one kind builds its arm: n joints, a function that creates the bodies
/// and joints in ODE's `world` at joint angles q and rates qdot (sizes
/// checked by the caller), sets the world's gravity, and returns the handle,
/// and the same arm as bodies for the other engines (a kind without them
/// runs on ODE only: plant.engine names the kind when it refuses).
struct ArmBuilder {
  int dof = 0;
  std::function<std::unique_ptr<ArmWorld>(dxWorld* world, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& qdot)>
      build;
  std::optional<ArmBodies> bodies{};
};

}  // namespace lagrange::plant
