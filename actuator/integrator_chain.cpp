#include "actuator/integrator_chain.hpp"

#include <stdexcept>
#include <string>

namespace lagrange::actuator {

IntegratorChain::IntegratorChain(int dof, int order, std::optional<Eigen::VectorXd> saturation,
                                 Eigen::MatrixXd initial)
    : dof_(dof), order_(order), saturation_(std::move(saturation)), xi_(std::move(initial)) {
  if (order_ < 0 || order_ > kMaxOrder)
    throw std::invalid_argument("actuator: order " + std::to_string(order_) + " is outside 0.." +
                                std::to_string(kMaxOrder));
  if (xi_.rows() != order_ || (order_ > 0 && xi_.cols() != dof_))
    throw std::invalid_argument("actuator: initial chain state must be " + std::to_string(order_) + " x " +
                                std::to_string(dof_) + " (one row per integrator)");
  if (!xi_.allFinite()) throw std::invalid_argument("actuator: initial chain state must be finite");
  if (saturation_) {
    if (saturation_->size() != dof_)
      throw std::invalid_argument("actuator: saturation has " + std::to_string(saturation_->size()) +
                                  " entries, expected " + std::to_string(dof_));
    if (!(saturation_->array() > 0.0).all())
      throw std::invalid_argument("actuator: saturation limits must be positive");
  }
}

Eigen::VectorXd IntegratorChain::clip(const Eigen::VectorXd& tau) const {
  return saturation_ ? Eigen::VectorXd(tau.cwiseMax(-*saturation_).cwiseMin(*saturation_)) : tau;
}

void IntegratorChain::advance(const Eigen::VectorXd& u, double dt) {
  if (u.size() != dof_)
    throw std::invalid_argument("actuator: command has " + std::to_string(u.size()) + " entries, expected " +
                                std::to_string(dof_));
  if (!(dt > 0.0)) throw std::invalid_argument("actuator: dt must be positive");
  // Row by row from the top: xi_i(T) uses the old xi_j for j >= i only.
  for (int i = 0; i < order_; ++i) {
    Eigen::VectorXd next = Eigen::VectorXd::Zero(dof_);
    double coefficient = 1.0;  // T^(j-i) / (j-i)!
    for (int j = i; j < order_; ++j) {
      next += coefficient * xi_.row(j).transpose();
      coefficient *= dt / static_cast<double>(j - i + 1);
    }
    next += coefficient * u;  // T^(m-i) / (m-i)! in 0-based rows
    xi_.row(i) = next.transpose();
  }
}

ActuatorOutput IntegratorChain::step(const Eigen::VectorXd& u, double dt, int steps) {
  if (u.size() != dof_)
    throw std::invalid_argument("actuator: command has " + std::to_string(u.size()) + " entries, expected " +
                                std::to_string(dof_));
  if (steps < 1) throw std::invalid_argument("actuator: steps per period must be at least 1");
  ActuatorOutput out;
  out.tau.resize(steps, dof_);
  out.saturated = Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(dof_, false);
  for (int s = 0; s < steps; ++s) {
    const Eigen::VectorXd raw = order_ == 0 ? u : Eigen::VectorXd(xi_.row(0).transpose());
    const Eigen::VectorXd applied = clip(raw);
    out.tau.row(s) = applied.transpose();
    out.saturated = out.saturated || (applied.array() != raw.array());
    if (order_ > 0) advance(u, dt / steps);
  }
  return out;
}

}  // namespace lagrange::actuator
