#pragma once
/// @file
/// Channel names of DESIGN section 4, in one place.

#include <string>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"

namespace lagrange::transport {
inline constexpr const char* kPlantPosition = "PLANT_POSITION";
inline constexpr const char* kPlantTruth = "PLANT_TRUTH";
inline constexpr const char* kPlantMotor = "PLANT_MOTOR";  // flexible joints only
inline constexpr const char* kPlantRate = "PLANT_RATE";    // with a velocity sensor only
inline constexpr const char* kControlCommand = "CONTROL_COMMAND";
inline constexpr const char* kActuatorState = "ACTUATOR_STATE";
inline constexpr const char* kStatus = "STATUS";
inline constexpr const char* kScenario = "SCENARIO";
inline constexpr const char* kRobotDescription = "ROBOT_DESCRIPTION";
/// The launchers of a run spread over hosts agreeing on the run's fresh
/// value before its processes start (lagrange/run_join_t.hpp); signed with
/// the shared key, never with the run's, and never recorded.
inline constexpr const char* kRunJoin = "RUN_JOIN";

/// What the project knows of each of its channels besides the message type
/// (withChannelMessage below): who publishes it, and whether it carries one
/// message per tick of the run.
struct ChannelInfo {
  const char* name;
  const char* publisher;  ///< the only process publishing it; "" for STATUS (every process)
  bool per_tick;          ///< one message per tick: recorded, covered, exported, replayed
  /// Exists only in some runs: PLANT_MOTOR for flexible joints, PLANT_RATE
  /// with a velocity sensor (sensors.velocity).
  enum class Only { kAlways, kFlexible, kVelocitySensor } only;
};

/// Which of the optional per-tick channels a run has.
struct RunChannels {
  bool flexible = false;         ///< PLANT_MOTOR
  bool velocity_sensor = false;  ///< PLANT_RATE
};

/// The channel registry: every channel of DESIGN section 4, per-tick ones in
/// publishing order.
inline constexpr ChannelInfo kChannelTable[] = {
    {kPlantPosition, "plant", true, ChannelInfo::Only::kAlways},
    {kPlantTruth, "plant", true, ChannelInfo::Only::kAlways},
    {kPlantMotor, "plant", true, ChannelInfo::Only::kFlexible},
    {kPlantRate, "plant", true, ChannelInfo::Only::kVelocitySensor},
    {kControlCommand, "controller", true, ChannelInfo::Only::kAlways},
    {kActuatorState, "actuator", true, ChannelInfo::Only::kAlways},
    {kStatus, "", false, ChannelInfo::Only::kAlways},
    {kScenario, "logger", false, ChannelInfo::Only::kAlways},
    {kRobotDescription, "logger", false, ChannelInfo::Only::kAlways},
    {kRunJoin, "launcher", false, ChannelInfo::Only::kAlways},
};

/// The only process that publishes on `channel`, or "" for STATUS (every
/// process) and channels of others.
inline const char* publisherOf(const std::string& channel) {
  for (const ChannelInfo& info : kChannelTable)
    if (channel == info.name) return info.publisher;
  return "";
}

/// The per-tick channels of a run: PLANT_MOTOR only with flexible joints,
/// PLANT_RATE only with a velocity sensor.
inline std::vector<std::string> perTickChannels(RunChannels run) {
  std::vector<std::string> channels;
  for (const ChannelInfo& info : kChannelTable) {
    const bool exists = info.only == ChannelInfo::Only::kAlways ||
                        (info.only == ChannelInfo::Only::kFlexible && run.flexible) ||
                        (info.only == ChannelInfo::Only::kVelocitySensor && run.velocity_sensor);
    if (info.per_tick && exists) channels.emplace_back(info.name);
  }
  return channels;
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
  if (channel == kPlantRate) return f(lagrange::plant_rate_t{});
  if (channel == kControlCommand) return f(lagrange::control_command_t{});
  if (channel == kActuatorState) return f(lagrange::actuator_state_t{});
  return otherwise;
}
}  // namespace lagrange::transport
