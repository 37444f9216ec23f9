#include "controller/scenario_controller.hpp"

namespace lagrange::controller {

ScenarioController::ScenarioController(const config::Scenario& s)
    : chain_(s.robot), reference_(s.reference), order_(s.actuator.order) {
  if (s.controller.type == "cascaded") {
    cascaded_.emplace(chain_, reference_, CascadedGains{s.controller.gains, s.controller.stages},
                      s.controller.initial_filter_state);
  } else {
    theorem1_.emplace(chain_, reference_, s.controller.gains, s.controller.initial_filter_state);
  }
}

Theorem1Output ScenarioController::step(double t, const Eigen::VectorXd& q, const Eigen::MatrixXd& xi) {
  if (theorem1_) return theorem1_->step(t, q);
  const CascadedController::Output out = cascaded_->step(t, q, xi);
  Theorem1Output command = out.stage0;
  command.u = out.cascade.u;
  command.xi_error = out.cascade.xi_error;
  return command;
}

}  // namespace lagrange::controller
