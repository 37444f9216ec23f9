#include "controller/pd_plus_differenced.hpp"

#include <stdexcept>
#include <string>
#include <utility>

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
  Theorem1Output out;
  out.q_desired = r.q();
  out.q_error = q - r.q();
  out.theta = v;
  // D q_d'' + C(q, v) q_d' + g: the Coriolis term has the measured (here:
  // differenced) velocity in its first slot, as in PD+.
  out.u = model_.inertia(q) * r.qdd() + model_.coriolisTimes(q, v, r.qd()) + model_.gravity(q) -
          kp_.cwiseProduct(out.q_error) - kd_.cwiseProduct(v - r.qd());
  previous_ = Sample{t, q};
  return out;
}

}  // namespace lagrange::controller
