#include "transport/messages.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <initializer_list>

#include "transport/process_state.hpp"

namespace lagrange::transport {

lagrange::header_t makeHeader(int64_t tick, double sim_time) {
  lagrange::header_t h{};  // run_id, publisher and seq: stamped by LcmNode::publish
  h.tick = tick;
  h.sim_time = sim_time;
  h.publish_utime = nowUtime();
  return h;
}

Eigen::VectorXd toEigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

Eigen::MatrixXd toEigen(const std::vector<std::vector<double>>& rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()),
                    rows.empty() ? 0 : static_cast<Eigen::Index>(rows[0].size()));
  for (size_t i = 0; i < rows.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = toEigen(rows[i]).transpose();
  return m;
}

std::vector<double> toStd(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

namespace {
std::string checkHeader(const lagrange::header_t& h) {
  if (h.tick < 0) return "negative tick";
  if (!std::isfinite(h.sim_time) || h.sim_time < 0.0) return "sim_time not finite or negative";
  return "";
}

std::string checkArrays(int32_t num_joints, int joints,
                        std::initializer_list<const std::vector<double>*> arrays) {
  if (num_joints != joints)
    return "num_joints is " + std::to_string(num_joints) + ", expected " + std::to_string(joints);
  for (const auto* a : arrays) {
    if (static_cast<int>(a->size()) != joints) return "array size differs from num_joints";
    for (double x : *a)
      if (!std::isfinite(x)) return "non-finite value (NaN or Inf)";
  }
  return "";
}

// A plant's state past any arm's range: finite, yet no joint turns 1e9 rad
// (1.6e8 turns) or slides 1e9 m in a run, and the controllers' arithmetic
// would overflow on it -- so a plant's 1e308 is refused as the plant's, not
// taken for a controller's infinite command one step later.
std::string checkPlausible(std::initializer_list<const std::vector<double>*> arrays) {
  for (const auto* a : arrays)
    for (size_t j = 0; j < a->size(); ++j)
      if (std::abs((*a)[j]) > kPlausibleState) {
        char value[32];
        std::snprintf(value, sizeof value, "%.6g", (*a)[j]);
        return std::string("value ") + value + " of joint " + std::to_string(j + 1) +
               " is past any arm's range (|q|, |q'| at most 1e9)";
      }
  return "";
}
}  // namespace

std::string validate(const lagrange::plant_position_t& m, int joints) {
  std::string why = checkHeader(m.header);
  if (why.empty()) why = checkArrays(m.num_joints, joints, {&m.q});
  return why.empty() ? checkPlausible({&m.q}) : why;
}

std::string validate(const lagrange::plant_rate_t& m, int joints) {
  std::string why = checkHeader(m.header);
  if (why.empty()) why = checkArrays(m.num_joints, joints, {&m.qdot});
  return why.empty() ? checkPlausible({&m.qdot}) : why;
}

std::string validate(const lagrange::plant_truth_t& m, int joints) {
  std::string why = checkHeader(m.header);
  if (why.empty()) why = checkArrays(m.num_joints, joints, {&m.q, &m.qdot, &m.tau_applied});
  if (why.empty()) why = checkPlausible({&m.q, &m.qdot});
  // NaN: not known (an external plant that does not compute the arm's
  // energy; docs/external_programs.md); an infinite energy is refused.
  if (why.empty() && std::isinf(m.total_energy)) why = "infinite energy";
  return why;
}

std::string validate(const lagrange::plant_motor_t& m, int joints, bool with_rates) {
  std::string why = checkHeader(m.header);
  if (why.empty()) why = checkArrays(m.num_joints, joints, {&m.q});
  const int rates = with_rates ? joints : 0;
  if (why.empty() && (m.num_rates != rates || static_cast<int>(m.qdot.size()) != rates))
    why = "num_rates is " + std::to_string(m.num_rates) + ", expected " + std::to_string(rates) +
          (with_rates ? " (robot.flexible.rate_sensor is true)" : " (no motor rate sensor)");
  for (double x : m.qdot)
    if (why.empty() && !std::isfinite(x)) why = "non-finite value (NaN or Inf)";
  return why.empty() ? checkPlausible({&m.q, &m.qdot}) : why;
}

std::string validate(const lagrange::control_command_t& m, int joints) {
  std::string why = checkHeader(m.header);
  if (why.empty())
    why = checkArrays(m.num_joints, joints, {&m.u, &m.q_desired, &m.q_error, &m.theta, &m.filter_state});
  if (why.empty() && (m.chain_order < 0 || static_cast<int>(m.xi_error.size()) != m.chain_order))
    why = "xi_error rows differ from chain_order";
  for (const auto& row : m.xi_error)
    if (why.empty()) why = checkArrays(m.num_joints, joints, {&row});
  return why;
}

std::string validate(const lagrange::actuator_state_t& m, int joints, int torque_steps) {
  std::string why = checkHeader(m.header);
  if (why.empty()) why = checkArrays(m.num_joints, joints, {&m.u_commanded});
  if (why.empty() && (m.torque_steps < 1 || static_cast<int>(m.tau_applied.size()) != m.torque_steps))
    why = "tau_applied rows differ from torque_steps (expected at least 1)";
  if (why.empty() && torque_steps > 0 && m.torque_steps != torque_steps)
    why = "torque_steps is " + std::to_string(m.torque_steps) + ", expected " + std::to_string(torque_steps) +
          " (actuator.rate / plant.publish_rate)";
  for (const auto& row : m.tau_applied)
    if (why.empty()) why = checkArrays(m.num_joints, joints, {&row});
  if (why.empty() && static_cast<int>(m.saturated.size()) != joints)
    why = "array size differs from num_joints";
  if (why.empty() && (m.order < 0 || static_cast<int>(m.xi.size()) != m.order))
    why = "xi rows differ from order";
  for (const auto& row : m.xi)
    if (why.empty()) why = checkArrays(m.num_joints, joints, {&row});
  return why;
}

std::string validateClock(const lagrange::header_t& h, long long last_tick, double period) {
  if (h.tick < 0 || h.tick > last_tick)
    return "tick " + std::to_string(h.tick) + " is outside the run (its ticks are 0 to " +
           std::to_string(last_tick) + ")";
  const double t = static_cast<double>(h.tick) * period;
  if (!(std::abs(h.sim_time - t) <= 1e-6 * period))
    return "sim_time " + std::to_string(h.sim_time) + " s is not its tick's time (tick " +
           std::to_string(h.tick) + " x " + std::to_string(period) + " s = " + std::to_string(t) +
           " s): the run's clock is tick / plant.publish_rate";
  return "";
}

std::string validate(const lagrange::status_t& m) {
  if (m.process.empty()) return "empty process name";
  if (!util::enumFrom(kProcessStateNames, m.state))
    return "unknown state '" + m.state + "'; expected " + util::choicesOf(kProcessStateNames);
  if (static_cast<int>(m.channels.size()) != m.num_channels) return "channel count mismatch";
  return checkHeader(m.header);
}

}  // namespace lagrange::transport
