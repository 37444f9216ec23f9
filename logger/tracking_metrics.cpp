#include "logger/tracking_metrics.hpp"

#include <cmath>

namespace lagrange::logger {

TrackingMetrics::TrackingMetrics(model::Reference reference, double tolerance, double xi_tolerance,
                                 double tick_period)
    : reference_(std::move(reference)),
      tolerance_(tolerance),
      tick_period_(tick_period),
      xi_tolerance_(xi_tolerance) {}

namespace {
// Final, max and convergence time of one error history.
ErrorSummary summarize(const std::vector<double>& times, const std::vector<double>& errors,
                       double tolerance) {
  ErrorSummary s;
  s.tolerance = tolerance;
  if (errors.empty()) return s;
  s.final_error = errors.back();
  std::optional<size_t> last_violation;
  for (size_t i = errors.size(); i-- > 0;) {
    s.max_error = std::max(s.max_error, errors[i]);
    if (!last_violation && errors[i] >= tolerance) last_violation = i;
  }
  if (!last_violation)
    s.convergence_time = times.front();
  else if (*last_violation + 1 < errors.size())
    s.convergence_time = times[*last_violation + 1];
  return s;
}
}  // namespace

void TrackingMetrics::addChainErrors(long long tick, double t,
                                     const std::vector<std::vector<double>>& xi_error) {
  if (tick <= last_chain_tick_ || xi_error.empty()) return;
  last_chain_tick_ = tick;
  chain_errors_.resize(xi_error.size());
  chain_times_.push_back(t);
  for (size_t i = 0; i < xi_error.size(); ++i)
    chain_errors_[i].push_back(
        Eigen::Map<const Eigen::VectorXd>(xi_error[i].data(), static_cast<Eigen::Index>(xi_error[i].size()))
            .norm());
}

void TrackingMetrics::watchVelocities(std::vector<std::string> joints, Eigen::VectorXd limits) {
  velocity_watch_.emplace();
  for (size_t i = 0; i < joints.size(); ++i)
    velocity_watch_->push_back({joints[i], limits(static_cast<Eigen::Index>(i)), 0.0, 0.0, 0});
  velocity_limits_ = std::move(limits);
}

std::optional<double> TrackingMetrics::addSample(long long tick, double t, const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& qdot) {
  if (tick < 0 || samples_.count(tick) > 0) return std::nullopt;
  if (velocity_watch_ && qdot.size() == velocity_limits_.size())
    for (Eigen::Index i = 0; i < qdot.size(); ++i) {
      VelocityCrossing& c = (*velocity_watch_)[static_cast<size_t>(i)];
      const double rate = std::abs(qdot(i));
      if (!(rate > c.limit)) continue;
      // Samples may come out of order (a re-sent one late): the earliest time counts.
      c.first_time = c.samples == 0 ? t : std::min(c.first_time, t);
      c.largest = std::max(c.largest, rate);
      ++c.samples;
    }
  // All joints at once: a free_motion reference integrates one step per
  // evaluation, so asking joint by joint cost n of them (the same values).
  const Eigen::VectorXd qd = reference_.evaluate(t, 0).q();
  const double e = (q - qd).norm();
  samples_.emplace(tick, Sample{t, e});
  while (samples_.count(contiguous_tick_ + 1) > 0) ++contiguous_tick_;
  return e;
}

void TrackingMetrics::addTorque(long long tick, const Eigen::MatrixXd& tau) {
  if (tau.size() > 0) torques_.emplace(tick, tau);
}

TrackingSummary TrackingMetrics::summary() const {
  TrackingSummary s;
  s.tolerance = tolerance_;
  if (velocity_watch_) {
    s.velocity_crossings.emplace();
    for (const VelocityCrossing& c : *velocity_watch_)
      if (c.samples > 0) s.velocity_crossings->push_back(c);
  }
  // The torques in tick order: a re-sent or late ACTUATOR_STATE counts once.
  const Eigen::RowVectorXd* previous = nullptr;
  Eigen::RowVectorXd last;
  long long saturated = 0;
  for (const auto& [tick, tau] : torques_) {
    if (saturation_ && tau.cols() == saturation_->size()) {
      const Eigen::RowVectorXd at_limit = saturation_->transpose() * (1.0 - 1e-9);
      bool any = false;
      for (Eigen::Index r = 0; r < tau.rows() && !any; ++r)
        any = (tau.row(r).cwiseAbs().array() >= at_limit.array()).any();
      saturated += any ? 1 : 0;
    }
    s.max_abs_torque = std::max(s.max_abs_torque, tau.cwiseAbs().maxCoeff());
    s.control_energy += tau.rowwise().squaredNorm().sum() * tick_period_ / static_cast<double>(tau.rows());
    for (Eigen::Index r = 0; r < tau.rows(); ++r) {
      if (previous) s.torque_total_variation += (tau.row(r) - *previous).cwiseAbs().sum();
      last = tau.row(r);
      previous = &last;
    }
  }
  if (saturation_ && !torques_.empty())  // no torque recorded: not measured
    s.saturated_fraction = static_cast<double>(saturated) / static_cast<double>(torques_.size());
  std::vector<double> times, errors;  // in tick order
  for (const auto& [tick, sample] : samples_) {
    times.push_back(sample.t);
    errors.push_back(sample.error);
  }
  s.samples = static_cast<long long>(errors.size());
  if (errors.empty()) return s;
  s.sim_time = times.back();
  s.final_error = errors.back();
  s.first_time = times.front();
  s.initial_error = errors.front();
  double sum_sq = 0.0;
  long long in_window = 0;
  // Walk backwards: the convergence time is the sample after the last one at
  // or above the tolerance.
  std::optional<size_t> last_violation;
  for (size_t i = errors.size(); i-- > 0;) {
    if (errors[i] >= s.max_error) {  // walking backwards: the earliest time of the largest
      s.max_error = errors[i];
      s.max_error_time = times[i];
    }
    if (!last_violation && errors[i] >= tolerance_) last_violation = i;
    if (times[i] >= s.sim_time - 1.0 - 1e-12) {
      sum_sq += errors[i] * errors[i];
      ++in_window;
    }
  }
  s.rms_last_second = std::sqrt(sum_sq / static_cast<double>(in_window));
  for (const auto& stage : chain_errors_) s.chain.push_back(summarize(chain_times_, stage, xi_tolerance_));
  if (!last_violation) {
    s.convergence_time = times.front();
  } else if (*last_violation + 1 < errors.size()) {
    s.convergence_time = times[*last_violation + 1];
  }
  return s;
}

}  // namespace lagrange::logger
