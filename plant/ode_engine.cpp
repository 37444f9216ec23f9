#include "plant/ode_engine.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "plant/joint_effects.hpp"
#include "plant/ode_body.hpp"

namespace lagrange::plant {

namespace {
// dInitODE2 is process-global and reference-counted by us, not by ODE.
std::mutex ode_init_mutex;
int ode_users = 0;

void acquireOde() {
  std::lock_guard<std::mutex> lock(ode_init_mutex);
  if (ode_users++ == 0) dInitODE2(0);
}
void releaseOde() {
  std::lock_guard<std::mutex> lock(ode_init_mutex);
  if (--ode_users == 0) dCloseODE();
}

double wrapToNearest(double wrapped, double predicted) {
  return wrapped + 2.0 * M_PI * std::round((predicted - wrapped) / (2.0 * M_PI));
}

// ODE's library is initialised for as long as one of these lives.
struct OdeLibrary {
  OdeLibrary() { acquireOde(); }
  ~OdeLibrary() { releaseOde(); }
  OdeLibrary(const OdeLibrary&) = delete;
  OdeLibrary& operator=(const OdeLibrary&) = delete;
};

class OdeEngine final : public PhysicsEngine {
 public:
  explicit OdeEngine(const EngineSetup& setup)
      : dof_(setup.arm.dof), physics_step_(setup.physics_step), flexible_(setup.flexible) {
    world_ = dWorldCreate();
    // A stepping dispatcher of this world's own: ODE's default one is a single
    // object per process, which two worlds stepped on two threads at once (the
    // sampled-data check's simulations) would share. The same self-threaded
    // kind as the default: the same computation in the same order.
    threading_ = dThreadingAllocateSelfThreadedImplementation();
    dWorldSetStepThreadingImplementation(world_, dThreadingImplementationGetFunctions(threading_),
                                         threading_);
    dWorldSetLinearDamping(world_, 0.0);
    dWorldSetAngularDamping(world_, 0.0);
    dWorldSetMaxAngularSpeed(world_, dInfinity);
    const JointPhysics& joints = setup.joints;
    try {
      arm_ = setup.arm.build(world_, setup.initial.q, setup.initial.qdot);
      q_ = setup.initial.q;
      if (flexible_) addRotors(setup.initial);
      if (joints.any())
        joint_effects_ = std::make_unique<JointEffects>(world_, arm_->hinges(),
                                                        JointLosses{joints.damping, joints.friction},
                                                        JointStops{joints.lower, joints.upper}, q_);
      if (joints.rotor_damping.size() > 0 || joints.rotor_friction.size() > 0) {
        if (!flexible_)
          throw std::invalid_argument("plant: rotor damping or friction without flexible joints");
        rotor_effects_ = std::make_unique<JointEffects>(
            world_, rotor_hinges_, JointLosses{joints.rotor_damping, joints.rotor_friction}, JointStops{},
            motor_q_, "rotor");
      }
    } catch (...) {  // the destructor does not run: give ODE's world back here
      destroy();
      throw;
    }
  }
  ~OdeEngine() override { destroy(); }

  void step(const Eigen::VectorXd& tau) override {
    // Joint torques: the input (rigid) or the springs' (flexible).
    const Eigen::VectorXd joint =
        flexible_ ? Eigen::VectorXd(flexible_->stiffness.cwiseProduct(motor_q_ - q_)) : tau;
    arm_->addJointTorques(joint);
    if (flexible_)
      for (int i = 0; i < dof_; ++i) dBodyAddTorque(rotors_[i], 0, 0, tau(i) - joint(i));
    if (joint_effects_) joint_effects_->beforeStep(q_);
    dWorldStep(world_, physics_step_);
    updateJointAngles();
    if (flexible_) updateMotorAngles();
    if (joint_effects_) joint_effects_->afterStep(arm_->jointRates(), physics_step_);
    if (rotor_effects_) rotor_effects_->afterStep(rotorRates(), physics_step_);
  }

  PlantState state() const override {
    PlantState s;
    s.q = q_;
    s.qdot = arm_->jointRates();
    if (flexible_) {
      s.motor_q = motor_q_;
      s.motor_qdot = rotorRates();
    }
    return s;
  }

  PlantEnergy energy() const override {
    PlantEnergy e;
    e.kinetic = arm_->kineticEnergy();
    e.potential = arm_->potentialEnergy();
    if (flexible_) {
      for (int i = 0; i < dof_; ++i) {
        const double w = dBodyGetAngularVel(rotors_[i])[2], twist = motor_q_(i) - q_(i);
        e.kinetic += 0.5 * flexible_->rotor_inertia(i) * w * w;
        e.potential += 0.5 * flexible_->stiffness(i) * twist * twist;
      }
    }
    return e;
  }

  double dissipated() const override {
    return (joint_effects_ ? joint_effects_->dissipated() : 0.0) +
           (rotor_effects_ ? rotor_effects_->dissipated() : 0.0);
  }

  double fastestBodyRate() const override {
    double worst = arm_->fastestBodyRate();
    for (dBodyID b : rotors_) worst = std::max(worst, std::abs(dBodyGetAngularVel(b)[2]));
    return worst;
  }

  std::string unsound() const override {
    bool finite = arm_->finite();
    for (dBodyID b : rotors_) finite = finite && bodyStateFinite(b);
    finite = finite && q_.allFinite() && (!flexible_ || motor_q_.allFinite());
    return finite ? "" : "the state is no longer finite";
  }

  double jointSeparation() const override { return arm_->jointSeparation(); }
  std::string name() const override { return "ODE"; }

 private:
  void addRotors(const PlantState& initial) {
    // Rotors on the base's z axis, below the plane of the links (no geoms:
    // nothing collides), each turning freely about its hinge.
    for (int i = 0; i < dof_; ++i) {
      dBodyID rotor = dBodyCreate(world_);
      dMass m;
      const double j = flexible_->rotor_inertia(i);
      dMassSetParameters(&m, 1.0, 0, 0, 0, j, j, j, 0, 0, 0);  // mass irrelevant: the hinge holds it
      dBodySetMass(rotor, &m);
      dBodySetPosition(rotor, 0.0, 0.0, -0.1 * (i + 1));
      dMatrix3 rot;
      dRFromAxisAndAngle(rot, 0, 0, 1, initial.motor_q(i));
      dBodySetRotation(rotor, rot);
      dBodySetAngularVel(rotor, 0, 0, initial.motor_qdot(i));
      dBodySetGyroscopicMode(rotor, 1);
      dJointID hinge = dJointCreateHinge(world_, nullptr);
      dJointAttach(hinge, rotor, nullptr);
      dJointSetHingeAnchor(hinge, 0.0, 0.0, -0.1 * (i + 1));
      dJointSetHingeAxis(hinge, 0, 0, 1);
      rotors_.push_back(rotor);
      rotor_hinges_.push_back(hinge);
    }
    motor_q_ = initial.motor_q;
  }

  void updateJointAngles() {
    const Eigen::VectorXd wrapped = arm_->wrappedJointAngles(), rates = arm_->jointRates();
    for (int i = 0; i < dof_; ++i) q_(i) = wrapToNearest(wrapped(i), q_(i) + rates(i) * physics_step_);
  }

  void updateMotorAngles() {
    const Eigen::VectorXd rates = rotorRates();
    for (int i = 0; i < dof_; ++i)
      motor_q_(i) = wrapToNearest(zRotation(rotors_[i]), motor_q_(i) + rates(i) * physics_step_);
  }

  Eigen::VectorXd rotorRates() const {
    Eigen::VectorXd rates(dof_);
    for (int i = 0; i < dof_; ++i) rates(i) = dBodyGetAngularVel(rotors_[i])[2];
    return rates;
  }

  void destroy() {
    joint_effects_.reset();
    rotor_effects_.reset();
    arm_.reset();
    if (world_) dWorldDestroy(world_);  // destroys bodies and joints too
    world_ = nullptr;
    if (threading_) dThreadingFreeImplementation(threading_);  // after the world that used it
    threading_ = nullptr;
  }

  OdeLibrary library_;  // first member: initialised before, closed after the world
  int dof_;
  double physics_step_;
  std::optional<model::FlexibleParams> flexible_;
  dWorldID world_ = nullptr;
  dThreadingImplementationID threading_ = nullptr;  ///< the world's own (see the constructor)
  std::unique_ptr<ArmWorld> arm_;
  std::vector<dBodyID> rotors_;  // flexible joints only
  std::vector<dJointID> rotor_hinges_;
  std::unique_ptr<JointEffects> joint_effects_, rotor_effects_;  // none without JointPhysics
  Eigen::VectorXd q_;                                            ///< continuous joint angles
  Eigen::VectorXd motor_q_;  ///< continuous motor angles (flexible joints)
};

}  // namespace

std::unique_ptr<PhysicsEngine> makeOdeEngine(const EngineSetup& setup) {
  return std::make_unique<OdeEngine>(setup);
}

}  // namespace lagrange::plant
