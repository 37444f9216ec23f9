#include "controller/velocity_feedback.hpp"

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

namespace lagrange::controller {

namespace {
void requirePositive(const char* who, int n, std::initializer_list<const Eigen::VectorXd*> gains) {
  for (const Eigen::VectorXd* gain : gains)
    if (gain->size() != n || !(gain->array() > 0.0).all())
      throw std::invalid_argument(std::string(who) + ": every gain must have " + std::to_string(n) +
                                  " positive entries");
}
}  // namespace

Theorem1Output pdPlusLaw(const model::RobotModel& model, const model::ReferenceSample& r,
                         const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& kp,
                         const Eigen::VectorXd& kd) {
  Theorem1Output out;
  out.q_desired = r.q();
  out.q_error = q - r.q();
  out.theta = v;
  // D q_d'' + C(q, v) q_d' + g: the Coriolis term has the velocity in its
  // first slot, as in Paden and Panja's PD+.
  out.u = model.inertia(q) * r.qdd() + model.coriolisTimes(q, v, r.qd()) + model.gravity(q) -
          kp.cwiseProduct(out.q_error) - kd.cwiseProduct(v - r.qd());
  return out;
}

PdPlus::PdPlus(const model::RobotModel& model, const model::Reference& reference, Eigen::VectorXd kp,
               Eigen::VectorXd kd)
    : model_(model), reference_(reference), kp_(std::move(kp)), kd_(std::move(kd)) {
  requirePositive("PdPlus", model_.dof(), {&kp_, &kd_});
}

Theorem1Output PdPlus::step(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot) const {
  return pdPlusLaw(model_, reference_.evaluate(t, 2), q, qdot, kp_, kd_);
}

SlotineLi::SlotineLi(const model::RobotModel& model, const model::Reference& reference,
                     Eigen::VectorXd lambda, Eigen::VectorXd kd)
    : model_(model), reference_(reference), lambda_(std::move(lambda)), kd_(std::move(kd)) {
  requirePositive("SlotineLi", model_.dof(), {&lambda_, &kd_});
}

Theorem1Output SlotineLi::step(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot) const {
  const model::ReferenceSample r = reference_.evaluate(t, 2);
  Theorem1Output out;
  out.q_desired = r.q();
  out.q_error = q - r.q();
  const Eigen::VectorXd qr_dot = r.qd() - lambda_.cwiseProduct(out.q_error);
  const Eigen::VectorXd qr_ddot = r.qdd() - lambda_.cwiseProduct(qdot - r.qd());
  const Eigen::VectorXd sliding = qdot - qr_dot;
  out.theta = qdot;
  out.filter_state = sliding;
  out.u = model_.inertia(q) * qr_ddot + model_.coriolisTimes(q, qdot, qr_dot) + model_.gravity(q) -
          kd_.cwiseProduct(sliding);
  return out;
}

}  // namespace lagrange::controller
