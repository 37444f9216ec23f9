#include "controller/dirty_derivative.hpp"

#include <stdexcept>

namespace lagrange::controller {

DirtyDerivativeFilter::DirtyDerivativeFilter(Eigen::VectorXd a, Eigen::VectorXd b, Eigen::VectorXd state)
    : a_(std::move(a)), b_(std::move(b)), state_(std::move(state)) {
  if (a_.size() != b_.size() || a_.size() != state_.size())
    throw std::invalid_argument("DirtyDerivativeFilter: a, b and state must have the same size");
  if ((a_.array() <= 0.0).any() || (b_.array() <= 0.0).any())
    throw std::invalid_argument("DirtyDerivativeFilter: a and b must be positive");
}

Eigen::VectorXd DirtyDerivativeFilter::output(const Eigen::VectorXd& x) const {
  return state_ + b_.cwiseProduct(x);
}

void DirtyDerivativeFilter::advance(const Eigen::VectorXd& x, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("DirtyDerivativeFilter: dt must be positive");
  const Eigen::ArrayXd decay = (-a_.array() * dt).exp();
  state_ = (decay * state_.array() - b_.array() * (1.0 - decay) * x.array()).matrix();
}

}  // namespace lagrange::controller
