#include "tools/replay/replay_fit.hpp"

#include <initializer_list>
#include <utility>
#include <vector>

namespace lagrange::tools::replay_log {

namespace {

constexpr const char* kJointsKey = "the arm's joints";

// "" when found == expected, else "holds FOUND NOUN(s) DETAIL, expected EXPECTED (KEY)".
std::string count(long long found, long long expected, const std::string& noun, const std::string& detail,
                  const std::string& key) {
  if (found == expected) return "";
  return "holds " + std::to_string(found) + " " + noun + (found == 1 ? "" : "s") + " " + detail +
         ", expected " + std::to_string(expected) + " (" + key + ")";
}

// The joint count and every per-joint array of a message.
std::string joints(int32_t num_joints, const MessageShape& shape,
                   std::initializer_list<std::pair<const char*, const std::vector<double>*>> arrays) {
  std::string why = count(num_joints, shape.joints, "joint", "(num_joints)", kJointsKey);
  for (const auto& [field, values] : arrays)
    if (why.empty())
      why = count(static_cast<long long>(values->size()), shape.joints, "value", std::string("in ") + field,
                  kJointsKey);
  return why;
}

// A table: `rows` rows of one value per joint.
std::string table(const std::vector<std::vector<double>>& values, long long rows, const char* field,
                  const char* row_noun, const std::string& key, const MessageShape& shape) {
  std::string why =
      count(static_cast<long long>(values.size()), rows, row_noun, std::string("in ") + field, key);
  for (size_t i = 0; why.empty() && i < values.size(); ++i)
    why = count(static_cast<long long>(values[i].size()), shape.joints, "value",
                std::string("in ") + field + "[" + std::to_string(i + 1) + "]", kJointsKey);
  return why;
}

}  // namespace

MessageShape shapeOf(const config::Scenario& s) {
  MessageShape shape;
  shape.joints = s.dof();
  shape.chain_order = s.actuator.order;
  shape.torque_steps = s.torqueStepsPerTick();
  shape.motor_rates = s.flexible && s.flexible->rate_sensor;
  return shape;
}

std::string misfit(const lagrange::plant_position_t& m, const MessageShape& shape) {
  return joints(m.num_joints, shape, {{"q", &m.q}});
}

std::string misfit(const lagrange::plant_rate_t& m, const MessageShape& shape) {
  return joints(m.num_joints, shape, {{"qdot", &m.qdot}});
}

std::string misfit(const lagrange::plant_motor_t& m, const MessageShape& shape) {
  std::string why = joints(m.num_joints, shape, {{"q", &m.q}});
  const int rates = shape.motor_rates ? shape.joints : 0;
  if (why.empty())
    why = count(m.num_rates, rates, "motor rate", "(num_rates)",
                shape.motor_rates ? "robot.flexible.rate_sensor is true" : "no motor rate sensor");
  if (why.empty())
    why = count(static_cast<long long>(m.qdot.size()), rates, "value", "in qdot",
                shape.motor_rates ? "robot.flexible.rate_sensor is true" : "no motor rate sensor");
  return why;
}

std::string misfit(const lagrange::plant_truth_t& m, const MessageShape& shape) {
  return joints(m.num_joints, shape, {{"q", &m.q}, {"qdot", &m.qdot}, {"tau_applied", &m.tau_applied}});
}

std::string misfit(const lagrange::control_command_t& m, const MessageShape& shape) {
  std::string why = joints(m.num_joints, shape,
                           {{"u", &m.u},
                            {"q_desired", &m.q_desired},
                            {"q_error", &m.q_error},
                            {"theta", &m.theta},
                            {"filter_state", &m.filter_state}});
  // How many stage errors a controller reports is its own (the cascaded one
  // one per chain stage, the flexible one two): a count the replayed core's
  // output is compared with. The table must hold what the count says.
  if (why.empty() && m.chain_order < 0)
    why = "holds " + std::to_string(m.chain_order) + " chain error rows (chain_order), expected 0 or more";
  if (why.empty())
    why = table(m.xi_error, m.chain_order, "xi_error", "chain error row", "its chain_order", shape);
  return why;
}

std::string misfit(const lagrange::actuator_state_t& m, const MessageShape& shape) {
  std::string why = joints(m.num_joints, shape, {{"u_commanded", &m.u_commanded}});
  if (why.empty())
    why =
        count(static_cast<long long>(m.saturated.size()), shape.joints, "value", "in saturated", kJointsKey);
  const std::string steps_key = "actuator.rate / plant.publish_rate";
  if (why.empty())
    why = count(m.torque_steps, shape.torque_steps, "torque step", "(torque_steps)", steps_key);
  if (why.empty())
    why = table(m.tau_applied, shape.torque_steps, "tau_applied", "torque step", steps_key, shape);
  if (why.empty()) why = count(m.order, shape.chain_order, "chain row", "(order)", "actuator.order");
  if (why.empty()) why = table(m.xi, shape.chain_order, "xi", "chain row", "actuator.order", shape);
  return why;
}

}  // namespace lagrange::tools::replay_log
