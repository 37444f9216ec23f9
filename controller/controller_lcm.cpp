#include "controller/controller_lcm.hpp"

#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange::controller {

void subscribeDeclaredInputs(transport::LcmNode& node, const Needs& needs, const MeasurementShape& shape,
                             InputAssembly& assembly) {
  // The callbacks run while the node is handled, after this returns: they
  // capture values, and the caller's assembly.
  if (needs.actuator_order > 0) {
    node.subscribe<lagrange::actuator_state_t>(
        transport::kActuatorState,
        [shape, order = needs.actuator_order](const lagrange::actuator_state_t& a) {
          const std::string why = transport::validate(a, shape.joints, shape.torque_steps_per_tick);
          if (!why.empty() || a.order == order) return why;
          return "actuator order is " + std::to_string(a.order) + ", expected " + std::to_string(order);
        },
        [&assembly](const lagrange::actuator_state_t& a) {
          assembly.chainState(a.header.tick, transport::toEigen(a.xi));
        });
  }
  if (needs.motor_angles) {
    node.subscribe<lagrange::plant_motor_t>(
        transport::kPlantMotor,
        [shape](const lagrange::plant_motor_t& m) {
          return transport::validate(m, shape.joints, shape.motor_rates);
        },
        [&assembly](const lagrange::plant_motor_t& m) {
          assembly.motorSample(m.header.tick, motorSample(m));
        });
  }
  if (needs.joint_rates) {
    node.subscribe<lagrange::plant_rate_t>(
        transport::kPlantRate,
        [shape](const lagrange::plant_rate_t& m) { return transport::validate(m, shape.joints); },
        [&assembly](const lagrange::plant_rate_t& m) {
          assembly.rateSample(m.header.tick, transport::toEigen(m.qdot));
        });
  }
}

using transport::toStd;

lagrange::control_command_t commandMessage(const Theorem1Output& out, int64_t position_tick, double sim_time,
                                           InputTicks inputs) {
  lagrange::control_command_t m;
  m.header = transport::makeHeader(position_tick, sim_time);
  m.input_position_tick = position_tick;
  m.input_actuator_tick = inputs.actuator;
  m.input_motor_tick = inputs.motor;
  m.num_joints = static_cast<int32_t>(out.u.size());
  m.u = toStd(out.u);
  const auto diagnostic = [&out](const Eigen::VectorXd& v) { return toStd(asPublished(v, out.u.size())); };
  m.q_desired = diagnostic(out.q_desired);
  m.q_error = diagnostic(out.q_error);
  m.theta = diagnostic(out.theta);
  m.filter_state = diagnostic(out.filter_state);
  m.chain_order = static_cast<int32_t>(out.xi_error.rows());
  for (int i = 0; i < out.xi_error.rows(); ++i) m.xi_error.push_back(toStd(out.xi_error.row(i).transpose()));
  return m;
}

Eigen::VectorXd asPublished(const Eigen::VectorXd& diagnostic, Eigen::Index joints) {
  return diagnostic.size() == 0 ? Eigen::VectorXd::Zero(joints) : diagnostic;
}

Eigen::MatrixXd motorSample(const lagrange::plant_motor_t& m) {
  const Eigen::VectorXd q2 = transport::toEigen(m.q);
  Eigen::MatrixXd sample(m.num_rates > 0 ? 2 : 1, q2.size());
  sample.row(0) = q2.transpose();
  if (m.num_rates > 0) sample.row(1) = transport::toEigen(m.qdot).transpose();
  return sample;
}

}  // namespace lagrange::controller
