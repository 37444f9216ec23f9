#include "controller/scenario_controller.hpp"

#include <stdexcept>

namespace lagrange::controller {

ScenarioController::ScenarioController(const config::Scenario& s)
    : chain_(s.controlModel()), reference_(s.reference), order_(s.actuator.order) {
  if (s.controller.type == "flexible") {
    flexible_.emplace(
        chain_, reference_, CascadedGains{s.controller.gains, s.controller.stages},
        s.controller.initial_filter_state, s.flexible->params,
        s.controller.motor_rate == "filtered" ? std::optional(s.controller.motor_rate_pole) : std::nullopt,
        s.controller.stage_starts);
  } else if (s.controller.type == "cascaded") {
    cascaded_.emplace(chain_, reference_, CascadedGains{s.controller.gains, s.controller.stages},
                      s.controller.initial_filter_state, s.controller.stage_starts);
  } else {
    theorem1_.emplace(chain_, reference_, s.controller.gains, s.controller.initial_filter_state);
  }
}

namespace {
Theorem1Output commandOf(const CascadedController::Output& out, const Eigen::VectorXd& u) {
  Theorem1Output command = out.stage0;
  command.u = u;
  command.xi_error = out.cascade.xi_error;
  return command;
}
}  // namespace

Theorem1Output ScenarioController::step(double t, const Eigen::VectorXd& q, const Eigen::MatrixXd& xi) {
  if (theorem1_) return theorem1_->step(t, q);
  if (flexible_) throw std::logic_error("ScenarioController: the flexible controller needs stepFlexible");
  const CascadedController::Output out = cascaded_->step(t, q, xi);
  return commandOf(out, out.cascade.u);
}

Theorem1Output ScenarioController::stepFlexible(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q2,
                                                const std::optional<Eigen::VectorXd>& q2dot) {
  if (!flexible_) throw std::logic_error("ScenarioController: stepFlexible on a rigid-joint controller");
  const FlexibleController::Output out = flexible_->step(t, q, q2, q2dot);
  return commandOf(out.cascade, out.tau);
}

}  // namespace lagrange::controller
