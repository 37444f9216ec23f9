#include "controller/nicosia_tomei.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace lagrange::controller {

NicosiaTomei::NicosiaTomei(const model::RobotModel& model, const model::Reference& reference,
                           NicosiaTomeiGains gains)
    : model_(model), reference_(reference), gains_(std::move(gains)) {
  for (const Eigen::VectorXd* gain : {&gains_.kp, &gains_.kd, &gains_.lp, &gains_.ld})
    if (gain->size() != model_.dof() || !(gain->array() > 0.0).all())
      throw std::invalid_argument("NicosiaTomei: kp, kd, lp and ld must have " +
                                  std::to_string(model_.dof()) + " positive entries");
}

std::pair<Eigen::VectorXd, Eigen::VectorXd> NicosiaTomei::derivative(const Eigen::VectorXd& q,
                                                                     const Eigen::VectorXd& u,
                                                                     const Eigen::VectorXd& zh,
                                                                     const Eigen::VectorXd& e) const {
  const Eigen::VectorXd qh_dot = zh + gains_.ld.cwiseProduct(e);
  // D^-1 (u - C(q, qh') qh' - g(q)): the model's forward dynamics at (q, qh').
  const Eigen::VectorXd zh_dot = model_.acceleration(q, qh_dot, u) + gains_.lp.cwiseProduct(e);
  return {qh_dot, zh_dot};
}

void NicosiaTomei::advance(State& s, double t) const {
  const double period = t - s.t;
  const double fastest = std::max(gains_.ld.maxCoeff(), std::sqrt(gains_.lp.maxCoeff()));
  const int substeps = std::max(1, static_cast<int>(std::ceil(period * fastest / 0.5)));
  const double h = period / substeps;
  // The innovation q_k - qh(t_k), taken at the sample where q is known, held
  // over the period with q_k and u_k.
  const Eigen::VectorXd e = s.q - s.qh;
  for (int i = 0; i < substeps; ++i) {
    const auto [a1, b1] = derivative(s.q, s.u, s.zh, e);
    const auto [a2, b2] = derivative(s.q, s.u, s.zh + h / 2 * b1, e);
    const auto [a3, b3] = derivative(s.q, s.u, s.zh + h / 2 * b2, e);
    const auto [a4, b4] = derivative(s.q, s.u, s.zh + h * b3, e);
    s.qh += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    s.zh += h / 6 * (b1 + 2 * b2 + 2 * b3 + b4);
  }
  s.t = t;
}

Theorem1Output NicosiaTomei::step(double t, const Eigen::VectorXd& q) {
  if (!state_) {
    state_ = State{t, q, Eigen::VectorXd::Zero(q.size()), q, Eigen::VectorXd::Zero(q.size())};
  } else {
    if (!(t > state_->t)) throw std::invalid_argument("NicosiaTomei: times must increase");
    advance(*state_, t);
  }
  State& s = *state_;
  const model::ReferenceSample r = reference_.evaluate(t, 2);
  const Eigen::VectorXd qh_dot = s.zh + gains_.ld.cwiseProduct(q - s.qh);
  Theorem1Output out;
  out.q_desired = r.q();
  out.q_error = q - r.q();
  out.theta = qh_dot;
  out.filter_state = s.qh;
  out.u = model_.inertia(q) * r.qdd() + model_.coriolisTimes(q, qh_dot, r.qd()) + model_.gravity(q) -
          gains_.kp.cwiseProduct(out.q_error) - gains_.kd.cwiseProduct(qh_dot - r.qd());
  s.q = q;
  s.u = out.u;
  return out;
}

}  // namespace lagrange::controller
