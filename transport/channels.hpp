#pragma once
/// @file
/// Channel names of DESIGN section 4, in one place.

namespace lagrange::transport {
inline constexpr const char* kPlantPosition = "PLANT_POSITION";
inline constexpr const char* kPlantTruth = "PLANT_TRUTH";
inline constexpr const char* kPlantMotor = "PLANT_MOTOR";  // flexible joints only
inline constexpr const char* kControlCommand = "CONTROL_COMMAND";
inline constexpr const char* kActuatorState = "ACTUATOR_STATE";
inline constexpr const char* kStatus = "STATUS";
inline constexpr const char* kScenario = "SCENARIO";
}  // namespace lagrange::transport
