#pragma once
/// @file
/// The controller a scenario asks for, behind one interface, so that the
/// controller process and the in-process runner build and call it alike:
/// "theorem1" (eq. 90, torque-driven arm) or "cascaded" (eq. 750, arm behind
/// an integrator chain of order actuator.order).

#include <memory>
#include <optional>

#include "config/scenario.hpp"
#include "controller/cascaded.hpp"
#include "controller/flexible.hpp"
#include "controller/theorem1.hpp"

namespace lagrange::controller {

class ScenarioController {
 public:
  explicit ScenarioController(const config::Scenario& scenario);
  ScenarioController(const ScenarioController&) = delete;  // the cores refer to chain_ and reference_
  ScenarioController& operator=(const ScenarioController&) = delete;

  /// The command at time t from the measured q and actuator chain state xi
  /// (m x n; empty for theorem1). The returned u is the command; q_desired,
  /// q_error, theta and filter_state are those of stage 0 (the dirty
  /// derivative of q~).
  Theorem1Output step(double t, const Eigen::VectorXd& q, const Eigen::MatrixXd& xi);

  /// The flexible controller (eq. 830): u is the motor torque tau, from the link
  /// angles q, the motor angles q2 and, when motor_rate is measured, q2'.
  Theorem1Output stepFlexible(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& q2,
                              const std::optional<Eigen::VectorXd>& q2dot);

  int order() const { return order_; }
  bool flexible() const { return flexible_.has_value(); }

 private:
  model::PlanarChain chain_;
  model::Reference reference_;
  int order_;
  std::optional<Theorem1Controller> theorem1_;
  std::optional<CascadedController> cascaded_;
  std::optional<FlexibleController> flexible_;
};

}  // namespace lagrange::controller
