#include "model/joint_springs.hpp"

#include <stdexcept>
#include <utility>

namespace lagrange::model {

JointSprings::JointSprings(RobotModelPtr links, Eigen::VectorXd stiffness)
    : links_(std::move(links)), stiffness_(std::move(stiffness)) {
  if (!links_) throw std::invalid_argument("JointSprings: no arm to add the springs to");
  if (stiffness_.size() != links_->dof() || !(stiffness_.array() > 0.0).all() || !stiffness_.allFinite())
    throw std::invalid_argument("JointSprings: the stiffness must be " + std::to_string(links_->dof()) +
                                " positive finite numbers [N m / rad]");
}

Eigen::VectorXd JointSprings::gravity(const Eigen::VectorXd& q) const {
  Eigen::VectorXd out = links_->gravity(q);
  out += stiffness_.cwiseProduct(q);
  return out;
}

Eigen::VectorXd JointSprings::inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                              const Eigen::VectorXd& a) const {
  Eigen::VectorXd out = links_->inverseDynamics(q, v, a);
  out += stiffness_.cwiseProduct(q);
  return out;
}

double JointSprings::potentialEnergy(const Eigen::VectorXd& q) const {
  double u = links_->potentialEnergy(q);
  u += 0.5 * q.dot(stiffness_.cwiseProduct(q));
  return u;
}

}  // namespace lagrange::model
