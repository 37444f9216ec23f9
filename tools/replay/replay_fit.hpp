#pragma once
/// @file
/// What a log's messages can honestly hold, given a scenario: the counts
/// replay reads from a message (joints, chain rows, torque steps, motor
/// rates) before it indexes anything with them. A message whose counts the
/// scenario does not give is never used: fed to a core it would be read past
/// its end (an ACTUATOR_STATE with one chain row more than the chain crashed
/// `replay --component actuator`), and compared it could make a false claim
/// (one with no rows compared nothing and "reproduced" them all).

#include <string>

#include "config/scenario.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"

namespace lagrange::tools::replay_log {

/// The counts a scenario fixes for its per-tick messages.
struct MessageShape {
  int joints = 0;            ///< the arm's joints
  int chain_order = 0;       ///< actuator.order: ACTUATOR_STATE's xi rows
  int torque_steps = 1;      ///< actuator.rate / plant.publish_rate: ACTUATOR_STATE's tau_applied rows
  bool motor_rates = false;  ///< robot.flexible.rate_sensor: PLANT_MOTOR carries q2'
};

MessageShape shapeOf(const config::Scenario& s);

/// "" when the message holds what `shape` gives, else the first count that
/// differs, found and expected: "holds 3 chain rows (xi), expected 2 (actuator.order)".
std::string misfit(const lagrange::plant_position_t& m, const MessageShape& shape);
std::string misfit(const lagrange::plant_rate_t& m, const MessageShape& shape);
std::string misfit(const lagrange::plant_motor_t& m, const MessageShape& shape);
std::string misfit(const lagrange::plant_truth_t& m, const MessageShape& shape);
std::string misfit(const lagrange::control_command_t& m, const MessageShape& shape);
std::string misfit(const lagrange::actuator_state_t& m, const MessageShape& shape);

}  // namespace lagrange::tools::replay_log
