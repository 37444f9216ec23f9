#include "controller/pd_plus_differenced.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "controller/velocity_feedback.hpp"

namespace lagrange::controller {

PdPlusDifferenced::PdPlusDifferenced(const model::RobotModel& model, const model::Reference& reference,
                                     Eigen::VectorXd kp, Eigen::VectorXd kd)
    : model_(model), reference_(reference), kp_(std::move(kp)), kd_(std::move(kd)) {
  for (const Eigen::VectorXd* gain : {&kp_, &kd_})
    if (gain->size() != model_.dof() || !(gain->array() > 0.0).all())
      throw std::invalid_argument("PdPlusDifferenced: kp and kd must have " + std::to_string(model_.dof()) +
                                  " positive entries");
}

Theorem1Output PdPlusDifferenced::step(double t, const Eigen::VectorXd& q) {
  const model::ReferenceSample r = reference_.evaluate(t, 2);
  const Eigen::VectorXd v = previous_ ? Eigen::VectorXd((q - previous_->q) / (t - previous_->t)) : r.qd();
  previous_ = Sample{t, q};
  return pdPlusLaw(model_, r, q, v, kp_, kd_);  // PD+ with the difference standing for the velocity
}

}  // namespace lagrange::controller
