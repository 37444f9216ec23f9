#include "plant/plant_sim.hpp"

#include <ode/ode.h>

#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

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

// Absolute angle of a body from the downward vertical: its rotation about z.
double bodyAngle(dBodyID body) {
  const dReal* r = dBodyGetRotation(body);  // 3x4 row-major
  return std::atan2(r[4], r[0]);
}

double wrapToNearest(double wrapped, double predicted) {
  return wrapped + 2.0 * M_PI * std::round((predicted - wrapped) / (2.0 * M_PI));
}
}  // namespace

struct PlantSim::Ode {
  dWorldID world = nullptr;
  std::vector<dBodyID> bodies;
  std::vector<dJointID> joints;
  std::vector<double> mass, inertia;
  ~Ode() {
    if (world) dWorldDestroy(world);  // destroys bodies and joints too
  }
};

PlantSim::PlantSim(const model::ChainParams& params, const PlantState& initial, double physics_step)
    : dof_(static_cast<int>(params.links.size())), physics_step_(physics_step), gravity_(params.gravity) {
  model::PlanarChain validated(params);  // validates the parameters
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
  dWorldSetGravity(ode_->world, 0.0, -params.gravity, 0.0);
  dWorldSetLinearDamping(ode_->world, 0.0);
  dWorldSetAngularDamping(ode_->world, 0.0);
  dWorldSetMaxAngularSpeed(ode_->world, dInfinity);

  // Place the bodies from the initial state.
  double phi = 0.0, phidot = 0.0;
  double jx = 0.0, jy = 0.0;    // position of the current joint
  double jvx = 0.0, jvy = 0.0;  // velocity of the current joint
  dBodyID parent = nullptr;
  for (int i = 0; i < dof_; ++i) {
    const model::LinkParams& link = params.links[i];
    phi += initial.q(i);
    phidot += initial.qdot(i);
    const double dx = std::sin(phi), dy = -std::cos(phi);                   // link direction
    const double vx = phidot * std::cos(phi), vy = phidot * std::sin(phi);  // d(direction)/dt

    dBodyID body = dBodyCreate(ode_->world);
    dMass m;
    // Body frame at the centre of mass; only the z inertia matters in the
    // plane, the others are set equal to keep the tensor positive definite.
    dMassSetParameters(&m, link.mass, 0, 0, 0, link.inertia, link.inertia, link.inertia, 0, 0, 0);
    dBodySetMass(body, &m);
    dBodySetPosition(body, jx + link.com * dx, jy + link.com * dy, 0.0);
    dMatrix3 rot;
    dRFromAxisAndAngle(rot, 0, 0, 1, phi);
    dBodySetRotation(body, rot);
    dBodySetLinearVel(body, jvx + link.com * vx, jvy + link.com * vy, 0.0);
    dBodySetAngularVel(body, 0, 0, phidot);
    dBodySetGyroscopicMode(body, 1);

    dJointID joint = dJointCreateHinge(ode_->world, nullptr);
    dJointAttach(joint, body, parent);  // parent == nullptr: the world
    dJointSetHingeAnchor(joint, jx, jy, 0.0);
    dJointSetHingeAxis(joint, 0, 0, 1);

    ode_->bodies.push_back(body);
    ode_->joints.push_back(joint);
    ode_->mass.push_back(link.mass);
    ode_->inertia.push_back(link.inertia);
    jx += link.length * dx;
    jy += link.length * dy;
    jvx += link.length * vx;
    jvy += link.length * vy;
    parent = body;
  }
  q_ = initial.q;
}

PlantSim::~PlantSim() {
  ode_.reset();
  releaseOde();
}

void PlantSim::updateJointAngles() {
  double previous_abs = 0.0, previous_rate = 0.0;
  for (int i = 0; i < dof_; ++i) {
    const double abs_angle = bodyAngle(ode_->bodies[i]);
    const double abs_rate = dBodyGetAngularVel(ode_->bodies[i])[2];
    const double rate = abs_rate - previous_rate;
    const double wrapped = std::remainder(abs_angle - previous_abs, 2.0 * M_PI);
    q_(i) = wrapToNearest(wrapped, q_(i) + rate * physics_step_);
    previous_abs = abs_angle;
    previous_rate = abs_rate;
  }
}

void PlantSim::step(const Eigen::VectorXd& tau, int substeps) {
  if (tau.size() != dof_)
    throw std::invalid_argument("plant: torque has " + std::to_string(tau.size()) + " entries, expected " +
                                std::to_string(dof_));
  for (int s = 0; s < substeps; ++s) {
    for (int i = 0; i < dof_; ++i) {
      dBodyAddTorque(ode_->bodies[i], 0, 0, tau(i));
      if (i > 0) dBodyAddTorque(ode_->bodies[i - 1], 0, 0, -tau(i));
    }
    dWorldStep(ode_->world, physics_step_);
    updateJointAngles();
    time_ += physics_step_;
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
  s.qdot.resize(dof_);
  double previous_rate = 0.0;
  for (int i = 0; i < dof_; ++i) {
    const double abs_rate = dBodyGetAngularVel(ode_->bodies[i])[2];
    s.qdot(i) = abs_rate - previous_rate;
    previous_rate = abs_rate;
  }
  return s;
}

PlantEnergy PlantSim::energy() const {
  PlantEnergy e;
  for (int i = 0; i < dof_; ++i) {
    const dReal* v = dBodyGetLinearVel(ode_->bodies[i]);
    const dReal* w = dBodyGetAngularVel(ode_->bodies[i]);
    const dReal* p = dBodyGetPosition(ode_->bodies[i]);
    e.kinetic += 0.5 * ode_->mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
                 0.5 * ode_->inertia[i] * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    e.potential += ode_->mass[i] * gravity_ * p[1];
  }
  return e;
}

}  // namespace lagrange::plant
