#include "controller/theorem1.hpp"

#include <stdexcept>
#include <string>

namespace lagrange::controller {

namespace {
void requirePositive(const Eigen::VectorXd& v, const char* name, int n) {
  if (v.size() != n)
    throw std::invalid_argument(std::string("Theorem1Controller: gain ") + name + " has " +
                                std::to_string(v.size()) + " entries, expected " + std::to_string(n));
  if (!(v.array() > 0.0).all() || !v.allFinite())
    throw std::invalid_argument(std::string("Theorem1Controller: gain ") + name +
                                " must be positive and finite");
}
}  // namespace

Theorem1Controller::Theorem1Controller(const model::RobotModel& chain, const model::Reference& reference,
                                       Theorem1Gains gains,
                                       std::optional<Eigen::VectorXd> initial_filter_state)
    : chain_(chain),
      reference_(reference),
      gains_(std::move(gains)),
      filter_(gains_.a, gains_.b, initial_filter_state.value_or(Eigen::VectorXd::Zero(gains_.a.size()))),
      bumpless_(!initial_filter_state) {
  const int n = chain_.dof();
  if (reference_.dof() != n)
    throw std::invalid_argument("Theorem1Controller: reference has " + std::to_string(reference_.dof()) +
                                " joints, robot has " + std::to_string(n));
  requirePositive(gains_.kp, "kp", n);
  requirePositive(gains_.kd, "kd", n);
  requirePositive(gains_.a, "a", n);
  requirePositive(gains_.b, "b", n);
  if (filter_.state().size() != n)
    throw std::invalid_argument("Theorem1Controller: initial filter state must have " + std::to_string(n) +
                                " entries");
}

Eigen::VectorXd Theorem1Controller::law(const model::ReferenceSample& ref, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& theta) const {
  const Eigen::VectorXd q_error = q - ref.q();
  const Eigen::VectorXd feedback = -gains_.kp.cwiseProduct(q_error) - gains_.kd.cwiseProduct(theta);
  return chain_.plusInverseDynamics(feedback, q, ref.qd(), ref.qdd());
}

Theorem1Output Theorem1Controller::step(double t, const Eigen::VectorXd& q) {
  Theorem1Output out;
  if (q.size() != chain_.dof())
    throw std::invalid_argument("Theorem1Controller: q has " + std::to_string(q.size()) +
                                " entries, expected " + std::to_string(chain_.dof()));
  if (has_previous_) {
    if (!(t > previous_time_))
      throw std::invalid_argument("Theorem1Controller: time must increase between steps");
    filter_.advance(previous_error_, t - previous_time_);
  }
  const model::ReferenceSample ref = reference_.evaluate(t, 2);
  out.q_desired = ref.q();
  out.q_error = q - out.q_desired;
  if (bumpless_ && !has_previous_) filter_.reset(-gains_.b.cwiseProduct(out.q_error));
  out.filter_state = filter_.state();
  out.theta = filter_.output(out.q_error);
  out.u = law(ref, q, out.theta);
  has_previous_ = true;
  previous_time_ = t;
  previous_error_ = out.q_error;
  return out;
}

}  // namespace lagrange::controller
