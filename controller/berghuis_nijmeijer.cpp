#include "controller/berghuis_nijmeijer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace lagrange::controller {

BerghuisNijmeijer::BerghuisNijmeijer(const model::RobotModel& model, const model::Reference& reference,
                                     BerghuisNijmeijerGains gains)
    : model_(model), reference_(reference), gains_(std::move(gains)) {
  for (const Eigen::VectorXd* gain : {&gains_.kp, &gains_.kd, &gains_.lambda, &gains_.lp, &gains_.ld})
    if (gain->size() != model_.dof() || !(gain->array() > 0.0).all())
      throw std::invalid_argument("BerghuisNijmeijer: kp, kd, lambda, lp and ld must have " +
                                  std::to_string(model_.dof()) + " positive entries");
}

void BerghuisNijmeijer::advance(State& s, double t) const {
  const double period = t - s.t;
  const double fastest =
      std::max({gains_.ld.maxCoeff(), std::sqrt(gains_.lp.maxCoeff()), gains_.lambda.maxCoeff()});
  const int substeps = std::max(1, static_cast<int>(std::ceil(period * fastest / 0.5)));
  const double h = period / substeps;
  const Eigen::VectorXd e = s.q - s.qh;  // the innovation at the sample, held (as Nicosia-Tomei's)
  // (qh', zh') at time tau: zh' = qr'' + Lp e, qr'' = q_d'' - Lambda (qh' - q_d').
  auto derivative = [&](double tau, const Eigen::VectorXd& zh) {
    const model::ReferenceSample r = reference_.evaluate(tau, 2);
    const Eigen::VectorXd qh_dot = zh + gains_.ld.cwiseProduct(e);
    const Eigen::VectorXd qr_ddot = r.qdd() - gains_.lambda.cwiseProduct(qh_dot - r.qd());
    return std::pair<Eigen::VectorXd, Eigen::VectorXd>{qh_dot, qr_ddot + gains_.lp.cwiseProduct(e)};
  };
  double tau = s.t;
  for (int i = 0; i < substeps; ++i, tau += h) {
    const auto [a1, b1] = derivative(tau, s.zh);
    const auto [a2, b2] = derivative(tau + h / 2, s.zh + h / 2 * b1);
    const auto [a3, b3] = derivative(tau + h / 2, s.zh + h / 2 * b2);
    const auto [a4, b4] = derivative(tau + h, s.zh + h * b3);
    s.qh += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    s.zh += h / 6 * (b1 + 2 * b2 + 2 * b3 + b4);
  }
  s.t = t;
}

Theorem1Output BerghuisNijmeijer::step(double t, const Eigen::VectorXd& q) {
  if (!state_) {
    state_ = State{t, q, q, Eigen::VectorXd::Zero(q.size())};
  } else {
    if (!(t > state_->t)) throw std::invalid_argument("BerghuisNijmeijer: times must increase");
    advance(*state_, t);
  }
  State& s = *state_;
  const model::ReferenceSample r = reference_.evaluate(t, 2);
  const Eigen::VectorXd& L = gains_.lambda;
  const Eigen::VectorXd qh_dot = s.zh + gains_.ld.cwiseProduct(q - s.qh);
  const Eigen::VectorXd qr_dot = r.qd() - L.cwiseProduct(s.qh - r.q());
  const Eigen::VectorXd qr_ddot = r.qdd() - L.cwiseProduct(qh_dot - r.qd());
  const Eigen::VectorXd q0_dot = qh_dot - L.cwiseProduct(s.qh - q);
  Theorem1Output out;
  out.q_desired = r.q();
  out.q_error = q - r.q();
  out.theta = qh_dot;
  out.filter_state = s.qh;
  out.u = model_.inertia(q) * qr_ddot + model_.coriolisTimes(q, q0_dot, qr_dot) + model_.gravity(q) -
          gains_.kd.cwiseProduct(q0_dot - qr_dot) - gains_.kp.cwiseProduct(out.q_error);
  s.q = q;
  return out;
}

}  // namespace lagrange::controller
