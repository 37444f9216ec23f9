#include "actuator/actuator_lcm.hpp"

#include "transport/messages.hpp"

namespace lagrange::actuator {

using transport::toStd;

lagrange::actuator_state_t actuatorMessage(const ActuatorOutput& out, const Eigen::MatrixXd& xi_next,
                                           const lagrange::control_command_t& command) {
  lagrange::actuator_state_t a;
  a.header = transport::makeHeader(command.header.tick, command.header.sim_time);
  a.input_command_tick = command.header.tick;
  a.num_joints = command.num_joints;
  a.order = static_cast<int32_t>(xi_next.rows());
  for (int i = 0; i < xi_next.rows(); ++i) a.xi.push_back(toStd(xi_next.row(i).transpose()));
  a.u_commanded = command.u;
  a.torque_steps = static_cast<int32_t>(out.tau.rows());
  for (int s = 0; s < out.tau.rows(); ++s) a.tau_applied.push_back(toStd(out.tau.row(s).transpose()));
  a.saturated.assign(out.saturated.data(), out.saturated.data() + out.saturated.size());
  return a;
}

}  // namespace lagrange::actuator
