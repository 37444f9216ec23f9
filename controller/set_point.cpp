#include "controller/set_point.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace lagrange::controller {

SetPoint::SetPoint(const model::RobotModel& model, const model::Reference& reference, Theorem1Gains gains)
    : model_(model),
      reference_(reference),
      gains_(std::move(gains)),
      filter_(gains_.a, gains_.b, Eigen::VectorXd::Zero(gains_.a.size())) {
  for (const Eigen::VectorXd* gain : {&gains_.kp, &gains_.kd, &gains_.a, &gains_.b})
    if (gain->size() != model_.dof() || !(gain->array() > 0.0).all())
      throw std::invalid_argument("SetPoint: kp, kd, a and b must have " + std::to_string(model_.dof()) +
                                  " positive entries");
}

Theorem1Output SetPoint::step(double t, const Eigen::VectorXd& q) {
  Theorem1Output out;
  out.q_desired = reference_.evaluate(t, 0).q();
  out.q_error = q - out.q_desired;
  if (previous_) {
    if (!(t > previous_->t)) throw std::invalid_argument("SetPoint: times must increase");
    filter_.advance(previous_->q, t - previous_->t);
  } else {
    filter_.reset(-gains_.b.cwiseProduct(q));  // bumpless: theta(t0) = 0
  }
  out.filter_state = filter_.state();
  out.theta = filter_.output(q);
  out.u = model_.gravity(q) - gains_.kp.cwiseProduct(out.q_error) - gains_.kd.cwiseProduct(out.theta);
  previous_ = Sample{t, q};
  return out;
}

}  // namespace lagrange::controller
