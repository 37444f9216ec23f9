#include "plant/urdf_arm_world.hpp"

#include <ode/ode.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "plant/ode_body.hpp"

namespace lagrange::plant {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Vector3d toEigen(const dReal* v) { return {v[0], v[1], v[2]}; }

class UrdfArmWorld final : public ArmWorld {
 public:
  UrdfArmWorld(const std::vector<model::UrdfBody>& bodies, double gravity, dWorldID world,
               const Eigen::VectorXd& q, const Eigen::VectorXd& qdot)
      : gravity_(gravity) {
    dWorldSetGravity(world, 0.0, 0.0, -gravity_);
    // At q = 0 first: every body with the base frame's axes, so that its
    // inertia tensor is the model's as it stands, and every hinge's zero
    // where the URDF has it.
    dBodyID parent = nullptr;
    for (const model::UrdfBody& b : bodies) {
      dBodyID body = dBodyCreate(world);
      dMass m;
      const Matrix3d& i = b.inertia;
      dMassSetParameters(&m, b.mass, 0, 0, 0, i(0, 0), i(1, 1), i(2, 2), i(0, 1), i(0, 2), i(1, 2));
      dBodySetMass(body, &m);
      dBodySetPosition(body, b.com.x(), b.com.y(), b.com.z());
      dBodySetGyroscopicMode(body, 1);
      dJointID joint = dJointCreateHinge(world, nullptr);
      dJointAttach(joint, body, parent);  // parent == nullptr: the world
      dJointSetHingeAnchor(joint, b.joint_anchor.x(), b.joint_anchor.y(), b.joint_anchor.z());
      dJointSetHingeAxis(joint, b.joint_axis.x(), b.joint_axis.y(), b.joint_axis.z());
      bodies_.push_back(body);
      joints_.push_back(joint);
      mass_.push_back(b.mass);
      inertia_.push_back(b.inertia);
      parent = body;
    }
    // Then to q: joint j turns every body after it about its axis, base to tip.
    const int n = dof();
    std::vector<Vector3d> com(n), anchor(n), axis(n);
    std::vector<Matrix3d> rotation(n, Matrix3d::Identity());
    for (int k = 0; k < n; ++k) {
      com[k] = bodies[k].com;
      anchor[k] = bodies[k].joint_anchor;
      axis[k] = bodies[k].joint_axis;
    }
    for (int j = 0; j < n; ++j) {
      const Matrix3d turn = Eigen::AngleAxisd(q(j), axis[j]).toRotationMatrix();
      const Vector3d c = anchor[j];
      for (int k = j; k < n; ++k) {
        com[k] = c + turn * (com[k] - c);
        rotation[k] = turn * rotation[k];
        if (k > j) {
          anchor[k] = c + turn * (anchor[k] - c);
          axis[k] = turn * axis[k];
        }
      }
    }
    // Rates: body k turns at sum_j<=k axis_j qdot_j, its centre moving with it.
    Vector3d omega = Vector3d::Zero();
    for (int k = 0; k < n; ++k) {
      omega += axis[k] * qdot(k);
      Vector3d v = Vector3d::Zero();
      for (int j = 0; j <= k; ++j) v += (axis[j] * qdot(j)).cross(com[k] - anchor[j]);
      dMatrix3 r;
      for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) r[4 * row + col] = rotation[k](row, col);
      r[3] = r[7] = r[11] = 0.0;
      dBodySetRotation(bodies_[k], r);
      dBodySetPosition(bodies_[k], com[k].x(), com[k].y(), com[k].z());
      dBodySetAngularVel(bodies_[k], omega.x(), omega.y(), omega.z());
      dBodySetLinearVel(bodies_[k], v.x(), v.y(), v.z());
    }
  }

  int dof() const override { return static_cast<int>(bodies_.size()); }

  void addJointTorques(const Eigen::VectorXd& tau) override {
    for (int i = 0; i < dof(); ++i) dJointAddHingeTorque(joints_[i], tau(i));
  }

  Eigen::VectorXd wrappedJointAngles() const override {
    Eigen::VectorXd q(dof());
    for (int i = 0; i < dof(); ++i) q(i) = dJointGetHingeAngle(joints_[i]);
    return q;
  }

  Eigen::VectorXd jointRates() const override {
    Eigen::VectorXd rates(dof());
    for (int i = 0; i < dof(); ++i) rates(i) = dJointGetHingeAngleRate(joints_[i]);
    return rates;
  }

  double fastestBodyRate() const override {
    double worst = 0.0;
    for (dBodyID b : bodies_) worst = std::max(worst, toEigen(dBodyGetAngularVel(b)).norm());
    return worst;
  }

  double jointSeparation() const override { return largestHingeSeparation(joints_); }
  std::vector<dJointID> hinges() const override { return joints_; }
  bool finite() const override { return allBodiesFinite(bodies_); }

  double kineticEnergy() const override {
    double e = 0.0;
    for (int i = 0; i < dof(); ++i) {
      const Vector3d v = toEigen(dBodyGetLinearVel(bodies_[i])), w = toEigen(dBodyGetAngularVel(bodies_[i]));
      const dReal* r = dBodyGetRotation(bodies_[i]);
      Matrix3d rot;
      for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) rot(row, col) = r[4 * row + col];
      e += 0.5 * mass_[i] * v.squaredNorm() + 0.5 * w.dot(rot * inertia_[i] * rot.transpose() * w);
    }
    return e;
  }

  double potentialEnergy() const override { return heightEnergy(bodies_, mass_, gravity_, 2); }

 private:
  double gravity_;
  std::vector<dBodyID> bodies_;
  std::vector<dJointID> joints_;
  std::vector<double> mass_;
  std::vector<Matrix3d> inertia_;  ///< about the centre of mass, in the body frame
};

}  // namespace

ArmBuilder urdfArmWorld(std::shared_ptr<const model::UrdfArm> arm) {
  return urdfArmWorld(arm->bodies(), arm->spec().gravity);
}

ArmBuilder urdfArmWorld(std::vector<model::UrdfBody> bodies, double gravity) {
  const int n = static_cast<int>(bodies.size());
  ArmBodies arm{{}, Eigen::Vector3d(0.0, 0.0, -gravity)};
  for (const model::UrdfBody& b : bodies)
    arm.bodies.push_back({b.joint_anchor, b.joint_axis, b.mass, b.com, b.inertia});
  return {n,
          [bodies = std::move(bodies), gravity](dWorldID world, const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& qdot) {
            return std::unique_ptr<ArmWorld>(std::make_unique<UrdfArmWorld>(bodies, gravity, world, q, qdot));
          },
          std::move(arm)};
}

}  // namespace lagrange::plant
