#pragma once
/// @file
/// Channel names of DESIGN section 4, in one place.

#include <string>

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
}  // namespace lagrange::transport
