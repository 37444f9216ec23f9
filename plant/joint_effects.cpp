#include "plant/joint_effects.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lagrange::plant {

namespace {
void checkPerJoint(const Eigen::VectorXd& v, size_t n, const std::string& what) {
  if (v.size() == 0) return;
  if (v.size() != static_cast<Eigen::Index>(n))
    throw std::invalid_argument("plant: " + what + " has " + std::to_string(v.size()) +
                                " entries, expected " + std::to_string(n));
  if (!v.allFinite() || (v.array() < 0.0).any())
    throw std::invalid_argument("plant: " + what + " must be finite numbers >= 0");
}

Eigen::Vector3d hingeAxis(dJointID hinge) {
  dVector3 a;
  dJointGetHingeAxis(hinge, a);
  return {a[0], a[1], a[2]};
}
}  // namespace

JointEffects::JointEffects(dWorldID world, const std::vector<dJointID>& hinges, const JointLosses& losses,
                           const JointStops& stops, const Eigen::VectorXd& q, const std::string& label)
    : hinges_(hinges), stops_(stops) {
  const size_t n = hinges.size();
  checkPerJoint(losses.damping, n, label + " damping");
  checkPerJoint(losses.friction, n, label + " friction");
  if (stops.any() &&
      (stops.lower.size() != static_cast<Eigen::Index>(n) ||
       stops.upper.size() != static_cast<Eigen::Index>(n) ||
       (stops.lower.array() > stops.upper.array()).any() || stops.lower.hasNaN() || stops.upper.hasNaN()))
    throw std::invalid_argument("plant: joint stops need " + std::to_string(n) +
                                " pairs with lower <= upper");
  for (size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    if (losses.damping.size() > 0 && losses.damping(k) > 0.0)
      motors_.push_back(motorOn(world, static_cast<int>(i), dInfinity, 1.0 / losses.damping(k)));
    if (losses.friction.size() > 0 && losses.friction(k) > 0.0)
      motors_.push_back(motorOn(world, static_cast<int>(i), losses.friction(k), std::nullopt));
  }
  if (stops_.any()) {
    for (dJointID h : hinges_) dJointSetHingeParam(h, dParamBounce, 0.0);
    beforeStep(q);
  }
}

JointEffects::~JointEffects() {
  for (Motor& m : motors_) dJointDestroy(m.amotor);
}

JointEffects::Motor JointEffects::motorOn(dWorldID world, int joint, double fmax, std::optional<double> cfm) {
  dJointID hinge = hinges_[static_cast<size_t>(joint)];
  Motor m{joint, dJointCreateAMotor(world, nullptr), std::make_unique<dJointFeedback>()};
  dJointAttach(m.amotor, dJointGetBody(hinge, 0), dJointGetBody(hinge, 1));
  dJointSetAMotorMode(m.amotor, dAMotorUser);
  dJointSetAMotorNumAxes(m.amotor, 1);
  const Eigen::Vector3d axis = hingeAxis(hinge);
  dJointSetAMotorAxis(m.amotor, 0, 1, axis.x(), axis.y(), axis.z());  // fixed in the moving body
  dJointSetAMotorParam(m.amotor, dParamVel, 0.0);
  dJointSetAMotorParam(m.amotor, dParamFMax, fmax);
  // The friction motor keeps the world's CFM (1e-10): a little regularisation,
  // since its row and a stop's on the same axis would otherwise make the LCP
  // singular when a rubbing joint rests on its stop.
  if (cfm) dJointSetAMotorParam(m.amotor, dParamCFM, *cfm);
  dJointSetFeedback(m.amotor, m.feedback.get());
  return m;
}

void JointEffects::beforeStep(const Eigen::VectorXd& q) {
  if (!stops_.any()) return;
  for (size_t i = 0; i < hinges_.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    // The hinge measures q minus this offset, within (-pi, pi].
    const double offset = q(k) - dJointGetHingeAngle(hinges_[i]);
    const double lo = stops_.lower(k) - offset, hi = stops_.upper(k) - offset;
    // ODE ignores a stop outside (-pi, pi]: none on that side in this wrap.
    dJointSetHingeParam(hinges_[i], dParamLoStop, lo >= -M_PI ? lo : -dInfinity);
    dJointSetHingeParam(hinges_[i], dParamHiStop, hi <= M_PI ? hi : dInfinity);
  }
}

void JointEffects::afterStep(const Eigen::VectorXd& rates, double h) {
  for (const Motor& m : motors_) {
    const Eigen::Vector3d axis = hingeAxis(hinges_[static_cast<size_t>(m.joint)]);
    const double torque = axis.dot(Eigen::Vector3d(m.feedback->t1[0], m.feedback->t1[1], m.feedback->t1[2]));
    dissipated_ -= torque * rates(m.joint) * h;
  }
}

}  // namespace lagrange::plant
