#pragma once
/// @file
/// Channel names of DESIGN section 4, in one place.

#include <string>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_truth_t.hpp"

namespace lagrange::transport {
inline constexpr const char* kPlantPosition = "PLANT_POSITION";
inline constexpr const char* kPlantTruth = "PLANT_TRUTH";
inline constexpr const char* kPlantMotor = "PLANT_MOTOR";  // flexible joints only
inline constexpr const char* kControlCommand = "CONTROL_COMMAND";
inline constexpr const char* kActuatorState = "ACTUATOR_STATE";
inline constexpr const char* kStatus = "STATUS";
inline constexpr const char* kScenario = "SCENARIO";

/// The only process that publishes on `channel`, or "" for STATUS (every
/// process) and channels of others.
inline const char* publisherOf(const std::string& channel) {
  if (channel == kPlantPosition || channel == kPlantTruth || channel == kPlantMotor) return "plant";
  if (channel == kControlCommand) return "controller";
  if (channel == kActuatorState) return "actuator";
  if (channel == kScenario) return "logger";
  return "";
}

/// The one dispatch from a per-tick channel's name to its message type: calls
/// f with a default-constructed message of the type `channel` carries and
/// returns its result, or `otherwise` for STATUS, SCENARIO and foreign
/// channels. Readers of logs (CSV export, replay) write one overload per
/// message type instead of an if-chain on channel names.
template <class R, class F>
R withChannelMessage(const std::string& channel, R otherwise, F&& f) {
  if (channel == kPlantPosition) return f(lagrange::plant_position_t{});
  if (channel == kPlantTruth) return f(lagrange::plant_truth_t{});
  if (channel == kPlantMotor) return f(lagrange::plant_motor_t{});
  if (channel == kControlCommand) return f(lagrange::control_command_t{});
  if (channel == kActuatorState) return f(lagrange::actuator_state_t{});
  return otherwise;
}
}  // namespace lagrange::transport
