#include "plant/planar_chain_world.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "plant/ode_body.hpp"

namespace lagrange::plant {

namespace {

class PlanarChainWorld final : public ArmWorld {
 public:
  PlanarChainWorld(const model::ChainParams& params, dWorldID world, const Eigen::VectorXd& q,
                   const Eigen::VectorXd& qdot)
      : gravity_(params.gravity) {
    dWorldSetGravity(world, 0.0, -params.gravity, 0.0);
    // Place the bodies from the initial state.
    double phi = 0.0, phidot = 0.0;
    double jx = 0.0, jy = 0.0;    // position of the current joint
    double jvx = 0.0, jvy = 0.0;  // velocity of the current joint
    dBodyID parent = nullptr;
    for (size_t i = 0; i < params.links.size(); ++i) {
      const model::LinkParams& link = params.links[i];
      phi += q(static_cast<Eigen::Index>(i));
      phidot += qdot(static_cast<Eigen::Index>(i));
      const double dx = std::sin(phi), dy = -std::cos(phi);                   // link direction
      const double vx = phidot * std::cos(phi), vy = phidot * std::sin(phi);  // d(direction)/dt

      dBodyID body = dBodyCreate(world);
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

      dJointID joint = dJointCreateHinge(world, nullptr);
      dJointAttach(joint, body, parent);  // parent == nullptr: the world
      dJointSetHingeAnchor(joint, jx, jy, 0.0);
      dJointSetHingeAxis(joint, 0, 0, 1);

      bodies_.push_back(body);
      joints_.push_back(joint);
      mass_.push_back(link.mass);
      inertia_.push_back(link.inertia);
      jx += link.length * dx;
      jy += link.length * dy;
      jvx += link.length * vx;
      jvy += link.length * vy;
      parent = body;
    }
  }

  int dof() const override { return static_cast<int>(bodies_.size()); }

  void addJointTorques(const Eigen::VectorXd& tau) override {
    for (int i = 0; i < dof(); ++i) {
      dBodyAddTorque(bodies_[i], 0, 0, tau(i));
      if (i > 0) dBodyAddTorque(bodies_[i - 1], 0, 0, -tau(i));
    }
  }

  Eigen::VectorXd wrappedJointAngles() const override {
    Eigen::VectorXd wrapped(dof());
    double previous_abs = 0.0;
    for (int i = 0; i < dof(); ++i) {
      const double abs_angle = zRotation(bodies_[i]);
      wrapped(i) = std::remainder(abs_angle - previous_abs, 2.0 * M_PI);
      previous_abs = abs_angle;
    }
    return wrapped;
  }

  Eigen::VectorXd jointRates() const override {
    Eigen::VectorXd rates(dof());
    double previous_rate = 0.0;
    for (int i = 0; i < dof(); ++i) {
      const double abs_rate = dBodyGetAngularVel(bodies_[i])[2];
      rates(i) = abs_rate - previous_rate;
      previous_rate = abs_rate;
    }
    return rates;
  }

  double fastestBodyRate() const override {
    double worst = 0.0;
    for (dBodyID b : bodies_) worst = std::max(worst, std::abs(dBodyGetAngularVel(b)[2]));
    return worst;
  }

  double jointSeparation() const override { return largestHingeSeparation(joints_); }
  std::vector<dJointID> hinges() const override { return joints_; }
  bool finite() const override { return allBodiesFinite(bodies_); }

  double kineticEnergy() const override {
    double e = 0.0;
    for (int i = 0; i < dof(); ++i) {
      const dReal* v = dBodyGetLinearVel(bodies_[i]);
      const dReal* w = dBodyGetAngularVel(bodies_[i]);
      e += 0.5 * mass_[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
           0.5 * inertia_[i] * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    }
    return e;
  }

  double potentialEnergy() const override { return heightEnergy(bodies_, mass_, gravity_, 1); }

 private:
  double gravity_;
  std::vector<dBodyID> bodies_;
  std::vector<dJointID> joints_;
  std::vector<double> mass_, inertia_;
};

}  // namespace

ArmBodies planarChainBodies(const model::ChainParams& params) {
  // At q = 0 the chain hangs along -y, every hinge on z; gravity -g along y.
  ArmBodies arm{{}, Eigen::Vector3d(0.0, -params.gravity, 0.0)};
  double joint_y = 0.0;
  for (const model::LinkParams& link : params.links) {
    ChainBody b;
    b.joint_anchor = Eigen::Vector3d(0.0, joint_y, 0.0);
    b.joint_axis = Eigen::Vector3d::UnitZ();
    b.mass = link.mass;
    b.com = Eigen::Vector3d(0.0, joint_y - link.com, 0.0);
    b.inertia = link.inertia * Eigen::Matrix3d::Identity();  // as ODE's body: only z matters in the plane
    arm.bodies.push_back(b);
    joint_y -= link.length;
  }
  return arm;
}

ArmBuilder planarChainWorld(const model::ChainParams& params) {
  const model::PlanarChain validated(params);  // refuses bad parameters before any ODE call
  return {validated.dof(),
          [params](dWorldID world, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot) {
            return std::unique_ptr<ArmWorld>(std::make_unique<PlanarChainWorld>(params, world, q, qdot));
          },
          planarChainBodies(params)};
}

}  // namespace lagrange::plant
