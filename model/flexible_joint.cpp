#include "model/flexible_joint.hpp"

#include <stdexcept>
#include <string>

namespace lagrange::model {

void validateFlexible(const FlexibleParams& p, int dof) {
  auto check = [dof](const Eigen::VectorXd& v, const char* what) {
    if (v.size() != dof)
      throw std::invalid_argument(std::string("flexible joints: ") + what + " has " +
                                  std::to_string(v.size()) + " entries, expected " + std::to_string(dof));
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if (!(v(i) > 0.0) || !std::isfinite(v(i)))
        throw std::invalid_argument(std::string("flexible joints: ") + what + " of joint " +
                                    std::to_string(i + 1) + " must be positive and finite, got " +
                                    std::to_string(v(i)));
  };
  check(p.stiffness, "stiffness");
  check(p.rotor_inertia, "rotor_inertia");
}

FlexibleChain::FlexibleChain(RobotModelPtr links, FlexibleParams params)
    : links_(std::move(links)), params_(std::move(params)) {
  if (!links_) throw std::invalid_argument("flexible joints: no arm for the joints to drive");
  validateFlexible(params_, links_->dof());
}

std::pair<Eigen::VectorXd, Eigen::VectorXd> FlexibleChain::acceleration(const FlexibleState& x,
                                                                        const Eigen::VectorXd& tau) const {
  const Eigen::VectorXd spring = params_.stiffness.cwiseProduct(x.q2 - x.q1);
  return {links_->acceleration(x.q1, x.v1, spring), (tau - spring).cwiseQuotient(params_.rotor_inertia)};
}

double FlexibleChain::energy(const FlexibleState& x) const {
  const Eigen::VectorXd twist = x.q2 - x.q1;
  return links_->kineticEnergy(x.q1, x.v1) + links_->potentialEnergy(x.q1) +
         0.5 * x.v2.dot(params_.rotor_inertia.cwiseProduct(x.v2)) +
         0.5 * twist.dot(params_.stiffness.cwiseProduct(twist));
}

}  // namespace lagrange::model
