#include "transport/builders.hpp"

#include "transport/messages.hpp"

namespace lagrange::transport {

lagrange::scenario_t scenarioMessage(const config::Scenario& s) {
  lagrange::scenario_t m;
  m.name = s.name;
  m.yaml = config::toYaml(s);
  return m;
}

PlantSample plantSample(int64_t tick, double sim_time, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                        const Eigen::VectorXd& tau_applied, double kinetic_energy, double potential_energy,
                        TorqueInput input) {
  PlantSample o;
  o.position.header = makeHeader(tick, sim_time);
  o.position.num_joints = static_cast<int32_t>(q.size());
  o.position.q = toStd(q);
  o.truth.header = o.position.header;
  o.truth.num_joints = o.position.num_joints;
  o.truth.q = o.position.q;
  o.truth.qdot = toStd(qdot);
  o.truth.tau_applied = toStd(tau_applied);
  o.truth.kinetic_energy = kinetic_energy;
  o.truth.potential_energy = potential_energy;
  o.truth.total_energy = kinetic_energy + potential_energy;
  o.truth.input_actuator_tick = input.actuator_tick;
  o.truth.torque_source = input.source;
  return o;
}

lagrange::control_command_t commandMessage(const controller::Theorem1Output& out, int64_t position_tick,
                                           double sim_time, InputTicks inputs) {
  lagrange::control_command_t m;
  m.header = makeHeader(position_tick, sim_time);
  m.input_position_tick = position_tick;
  m.input_actuator_tick = inputs.actuator;
  m.input_motor_tick = inputs.motor;
  m.num_joints = static_cast<int32_t>(out.u.size());
  m.u = toStd(out.u);
  m.q_desired = toStd(out.q_desired);
  m.q_error = toStd(out.q_error);
  m.theta = toStd(out.theta);
  m.filter_state = toStd(out.filter_state);
  m.chain_order = static_cast<int32_t>(out.xi_error.rows());
  for (int i = 0; i < out.xi_error.rows(); ++i) m.xi_error.push_back(toStd(out.xi_error.row(i).transpose()));
  return m;
}

lagrange::plant_motor_t motorMessage(int64_t tick, double sim_time, const Eigen::VectorXd& motor_q,
                                     const Eigen::VectorXd& motor_qdot, bool with_rates) {
  lagrange::plant_motor_t m;
  m.header = makeHeader(tick, sim_time);
  m.num_joints = static_cast<int32_t>(motor_q.size());
  m.q = toStd(motor_q);
  m.num_rates = with_rates ? m.num_joints : 0;
  if (with_rates) m.qdot = toStd(motor_qdot);
  return m;
}

std::optional<Eigen::VectorXd> motorRates(const lagrange::plant_motor_t& m) {
  if (m.num_rates == 0) return std::nullopt;
  return toEigen(m.qdot);
}

lagrange::actuator_state_t actuatorMessage(const actuator::ActuatorOutput& out,
                                           const Eigen::MatrixXd& xi_next,
                                           const lagrange::control_command_t& command) {
  lagrange::actuator_state_t a;
  a.header = makeHeader(command.header.tick, command.header.sim_time);
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

}  // namespace lagrange::transport
