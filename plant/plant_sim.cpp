#include "plant/plant_sim.hpp"

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
}  // namespace

struct PlantSim::Ode {
  dWorldID world = nullptr;
  std::unique_ptr<ArmWorld> arm;
  std::vector<dBodyID> rotors;  // flexible joints only
  std::vector<dJointID> rotor_hinges;
  std::unique_ptr<JointEffects> joint_effects, rotor_effects;  // none without JointPhysics
  ~Ode() {
    joint_effects.reset();
    rotor_effects.reset();
    arm.reset();
    if (world) dWorldDestroy(world);  // destroys bodies and joints too
  }
};

PlantSim::PlantSim(const ArmBuilder& arm, const PlantState& initial, double physics_step,
                   std::optional<model::FlexibleParams> flexible, std::optional<double> max_rate,
                   const JointPhysics& joints)
    : dof_(arm.dof), physics_step_(physics_step), flexible_(std::move(flexible)), max_rate_(max_rate) {
  if (max_rate_ && !(*max_rate_ > 0.0))
    throw std::invalid_argument("plant: max_rate must be positive, got " + std::to_string(*max_rate_));
  if (flexible_) {
    model::validateFlexible(*flexible_, dof_);
    if (initial.motor_q.size() != dof_ || initial.motor_qdot.size() != dof_)
      throw std::invalid_argument("plant: flexible joints need " + std::to_string(dof_) +
                                  " initial motor angles and rates");
    if (!initial.motor_q.allFinite() || !initial.motor_qdot.allFinite())
      throw std::invalid_argument("plant: initial motor state must be finite");
  }
  if (!(physics_step > 0.0) || !std::isfinite(physics_step))
    throw std::invalid_argument("plant: physics_step must be positive and finite");
  if (initial.q.size() != dof_ || initial.qdot.size() != dof_)
    throw std::invalid_argument("plant: initial state must have " + std::to_string(dof_) +
                                " joint angles and rates");
  if (!initial.q.allFinite() || !initial.qdot.allFinite())
    throw std::invalid_argument("plant: initial state must be finite");

  acquireOde();
  ode_ = std::make_unique<Ode>();
  ode_->world = dWorldCreate();
  dWorldSetLinearDamping(ode_->world, 0.0);
  dWorldSetAngularDamping(ode_->world, 0.0);
  dWorldSetMaxAngularSpeed(ode_->world, dInfinity);
  ode_->arm = arm.build(ode_->world, initial.q, initial.qdot);
  q_ = initial.q;

  if (flexible_) {
    // Rotors on the base's z axis, below the plane of the links (no geoms:
    // nothing collides), each turning freely about its hinge.
    for (int i = 0; i < dof_; ++i) {
      dBodyID rotor = dBodyCreate(ode_->world);
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
      dJointID hinge = dJointCreateHinge(ode_->world, nullptr);
      dJointAttach(hinge, rotor, nullptr);
      dJointSetHingeAnchor(hinge, 0.0, 0.0, -0.1 * (i + 1));
      dJointSetHingeAxis(hinge, 0, 0, 1);
      ode_->rotors.push_back(rotor);
      ode_->rotor_hinges.push_back(hinge);
    }
    motor_q_ = initial.motor_q;
  }
  try {
    if (joints.damping.size() > 0 || joints.friction.size() > 0 || joints.lower.size() > 0)
      ode_->joint_effects = std::make_unique<JointEffects>(ode_->world, ode_->arm->hinges(),
                                                           JointLosses{joints.damping, joints.friction},
                                                           JointStops{joints.lower, joints.upper}, q_);
    if (joints.rotor_damping.size() > 0 || joints.rotor_friction.size() > 0) {
      if (!flexible_) throw std::invalid_argument("plant: rotor damping or friction without flexible joints");
      ode_->rotor_effects = std::make_unique<JointEffects>(
          ode_->world, ode_->rotor_hinges, JointLosses{joints.rotor_damping, joints.rotor_friction},
          JointStops{}, motor_q_, "rotor");
    }
  } catch (...) {  // the destructor does not run: give ODE back here
    ode_.reset();
    releaseOde();
    throw;
  }
}

PlantSim::~PlantSim() {
  ode_.reset();
  releaseOde();
}

void PlantSim::updateJointAngles() {
  const Eigen::VectorXd wrapped = ode_->arm->wrappedJointAngles(), rates = ode_->arm->jointRates();
  for (int i = 0; i < dof_; ++i) q_(i) = wrapToNearest(wrapped(i), q_(i) + rates(i) * physics_step_);
}

void PlantSim::checkBounded() const {
  // See the class comment: only a failing simulation or the user's limit stops a run.
  double worst = ode_->arm->fastestBodyRate();
  bool finite = ode_->arm->finite();
  for (dBodyID b : ode_->rotors) {
    finite = finite && bodyStateFinite(b);
    worst = std::max(worst, std::abs(dBodyGetAngularVel(b)[2]));
  }
  // Built only when the run stops: formatting a double on every call was a
  // per-step cost (printf's float formatting showed in the plant's profile).
  const auto at = [this] { return "at t = " + std::to_string(time_) + " s"; };
  if (!finite || !q_.allFinite() || (flexible_ && !motor_q_.allFinite()))
    throw PlantStopped("plant: the simulation diverged " + at() + ": the state is no longer finite");
  const double resolvable = kMaxTurnPerStep / physics_step_;
  if (!(worst < resolvable))
    throw PlantStopped("plant: the simulation diverged " + at() + ": a body turns at " +
                       std::to_string(worst) + " rad/s, more than pi/2 per physics step (limit " +
                       std::to_string(resolvable) +
                       " rad/s at plant.physics_step = " + std::to_string(physics_step_) +
                       " s), which ODE cannot integrate; the closed loop is unstable, or needs a smaller "
                       "physics_step");
  if (max_rate_ && !(worst <= *max_rate_))
    throw PlantStopped("plant: stopped " + at() + ": a body turns at " + std::to_string(worst) +
                       " rad/s, above plant.max_rate = " + std::to_string(*max_rate_) + " rad/s");
}

void PlantSim::updateMotorAngles() {
  const Eigen::VectorXd rates = rotorRates();
  for (int i = 0; i < dof_; ++i)
    motor_q_(i) = wrapToNearest(zRotation(ode_->rotors[i]), motor_q_(i) + rates(i) * physics_step_);
}

void PlantSim::step(const Eigen::VectorXd& tau, int substeps) {
  if (tau.size() != dof_)
    throw std::invalid_argument("plant: torque has " + std::to_string(tau.size()) + " entries, expected " +
                                std::to_string(dof_));
  for (int s = 0; s < substeps; ++s) {
    // Joint torques: the input (rigid) or the springs' (flexible).
    const Eigen::VectorXd joint =
        flexible_ ? Eigen::VectorXd(flexible_->stiffness.cwiseProduct(motor_q_ - q_)) : tau;
    ode_->arm->addJointTorques(joint);
    if (flexible_)
      for (int i = 0; i < dof_; ++i) dBodyAddTorque(ode_->rotors[i], 0, 0, tau(i) - joint(i));
    if (ode_->joint_effects) ode_->joint_effects->beforeStep(q_);
    dWorldStep(ode_->world, physics_step_);
    updateJointAngles();
    if (flexible_) updateMotorAngles();
    if (ode_->joint_effects) ode_->joint_effects->afterStep(ode_->arm->jointRates(), physics_step_);
    if (ode_->rotor_effects) ode_->rotor_effects->afterStep(rotorRates(), physics_step_);
    time_ += physics_step_;
    checkBounded();
  }
}

void PlantSim::stepProfile(const Eigen::MatrixXd& tau, int substeps) {
  const int parts = static_cast<int>(tau.rows());
  if (parts < 1 || substeps % parts != 0)
    throw std::invalid_argument("plant: " + std::to_string(parts) + " torque steps do not divide " +
                                std::to_string(substeps) + " physics steps");
  for (int s = 0; s < parts; ++s) step(Eigen::VectorXd(tau.row(s).transpose()), substeps / parts);
}

PlantState PlantSim::state() const {
  PlantState s;
  s.q = q_;
  s.qdot = ode_->arm->jointRates();
  if (flexible_) {
    s.motor_q = motor_q_;
    s.motor_qdot = rotorRates();
  }
  return s;
}

double PlantSim::dissipated() const {
  return (ode_->joint_effects ? ode_->joint_effects->dissipated() : 0.0) +
         (ode_->rotor_effects ? ode_->rotor_effects->dissipated() : 0.0);
}

Eigen::VectorXd PlantSim::rotorRates() const {
  Eigen::VectorXd rates(dof_);
  for (int i = 0; i < dof_; ++i) rates(i) = dBodyGetAngularVel(ode_->rotors[i])[2];
  return rates;
}

double PlantSim::jointSeparation() const { return ode_->arm->jointSeparation(); }

PlantEnergy PlantSim::energy() const {
  PlantEnergy e;
  e.kinetic = ode_->arm->kineticEnergy();
  e.potential = ode_->arm->potentialEnergy();
  if (flexible_) {
    for (int i = 0; i < dof_; ++i) {
      const double w = dBodyGetAngularVel(ode_->rotors[i])[2], twist = motor_q_(i) - q_(i);
      e.kinetic += 0.5 * flexible_->rotor_inertia(i) * w * w;
      e.potential += 0.5 * flexible_->stiffness(i) * twist * twist;
    }
  }
  return e;
}

}  // namespace lagrange::plant
