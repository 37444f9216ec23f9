#include "controller/flexible.hpp"

#include <stdexcept>
#include <string>

namespace lagrange::controller {

FlexibleController::FlexibleController(const model::RobotModel& link_model, const model::Reference& reference,
                                       CascadedGains gains, std::optional<Eigen::VectorXd> qc0,
                                       model::FlexibleParams params, std::optional<Eigen::VectorXd> rate_pole,
                                       const std::vector<StageStart>& starts,
                                       std::optional<Eigen::VectorXd> rate_filter_start)
    : cascade_(link_model, reference, std::move(gains), std::move(qc0), starts), params_(std::move(params)) {
  model::validateFlexible(params_, link_model.dof());
  if (cascade_.order() != 2)
    throw std::invalid_argument("FlexibleController: expected 2 stages (m = 2), got " +
                                std::to_string(cascade_.order()));
  if (rate_pole) {
    rate_pole_ = *rate_pole;
    rate_filter_.emplace(rate_pole_, rate_pole_, Eigen::VectorXd::Zero(link_model.dof()));
    if (rate_filter_start) {
      if (rate_filter_start->size() != link_model.dof() || !rate_filter_start->allFinite())
        throw std::invalid_argument("FlexibleController: the rate filter's start must have " +
                                    std::to_string(link_model.dof()) + " finite entries");
      rate_filter_->reset(*rate_filter_start);
      rate_filter_bumpless_ = false;
    }
  }
}

FlexibleController::Output FlexibleController::step(double t, const Eigen::VectorXd& q1,
                                                    const Eigen::VectorXd& q2,
                                                    const std::optional<Eigen::VectorXd>& q2dot) {
  const Eigen::Index n = params_.stiffness.size();
  if (q1.size() != n || q2.size() != n)
    throw std::invalid_argument("FlexibleController: q1 and q2 must have " + std::to_string(n) + " entries");
  Output out;
  if (rate_filter_) {
    if (!has_previous_) {
      if (rate_filter_bumpless_)
        rate_filter_->reset(-rate_pole_.cwiseProduct(q2));  // the estimate starts at 0
    } else {
      rate_filter_->advance(previous_q2_, t - previous_time_);  // exact for q2 held between samples
    }
    out.motor_rate = rate_filter_->output(q2);
  } else {
    if (!q2dot || q2dot->size() != n)
      throw std::invalid_argument("FlexibleController: motor_rate measured, but no q2' of " +
                                  std::to_string(n) + " entries was given");
    out.motor_rate = *q2dot;
  }
  Eigen::MatrixXd xi(2, n);
  xi.row(0) = params_.stiffness.cwiseProduct(q2).transpose();
  xi.row(1) = params_.stiffness.cwiseProduct(out.motor_rate).transpose();
  out.cascade = cascade_.step(t, q1, xi);
  out.tau = params_.stiffness.cwiseProduct(q2 - q1) +
            params_.rotor_inertia.cwiseProduct(out.cascade.cascade.u).cwiseQuotient(params_.stiffness);
  has_previous_ = true;
  previous_time_ = t;
  previous_q2_ = q2;
  return out;
}

}  // namespace lagrange::controller
