#include "plant/plant_lcm.hpp"

#include "transport/messages.hpp"

namespace lagrange::plant {

using transport::makeHeader;
using transport::toEigen;
using transport::toStd;

PlantSample plantSample(int64_t tick, double sim_time, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                        const Eigen::VectorXd& tau_applied, double kinetic_energy, double potential_energy,
                        TorqueInput input, const Eigen::VectorXd& q_measured) {
  PlantSample o;
  o.position.header = makeHeader(tick, sim_time);
  o.position.num_joints = static_cast<int32_t>(q.size());
  o.position.q = toStd(q_measured);
  o.truth.header = o.position.header;
  o.truth.num_joints = o.position.num_joints;
  o.truth.q = toStd(q);
  o.truth.qdot = toStd(qdot);
  o.truth.tau_applied = toStd(tau_applied);
  o.truth.kinetic_energy = kinetic_energy;
  o.truth.potential_energy = potential_energy;
  o.truth.total_energy = kinetic_energy + potential_energy;
  o.truth.input_actuator_tick = input.actuator_tick;
  o.truth.torque_source = input.source;
  return o;
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

lagrange::plant_rate_t rateMessage(int64_t tick, double sim_time, const Eigen::VectorXd& qdot_measured) {
  lagrange::plant_rate_t m;
  m.header = makeHeader(tick, sim_time);
  m.num_joints = static_cast<int32_t>(qdot_measured.size());
  m.qdot = toStd(qdot_measured);
  return m;
}

std::optional<Eigen::VectorXd> motorRates(const lagrange::plant_motor_t& m) {
  if (m.num_rates == 0) return std::nullopt;
  return toEigen(m.qdot);
}

}  // namespace lagrange::plant
