#pragma once
/// @file
/// ACTUATOR_STATE from the actuator core's output: one place, used by the
/// actuator process and the in-process runner alike.

#include <Eigen/Dense>

#include "actuator/integrator_chain.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"

namespace lagrange::actuator {

/// xi_next: the chain state at the end of the period (m x n), what the
/// controller measures at the next tick.
lagrange::actuator_state_t actuatorMessage(const ActuatorOutput& out, const Eigen::MatrixXd& xi_next,
                                           const lagrange::control_command_t& command);

}  // namespace lagrange::actuator
