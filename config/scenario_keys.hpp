#pragma once
/// @file
/// The keys of the scenario file's sections with hand-written readers (they
/// depend on other sections: joint counts, the controller's type): each
/// reader rejects every key not listed here (MapReader::finish), and
/// documentedKeys() lists them with the field-described sections
/// (config/fields.hpp) for the test that holds docs/configuration.md to them.

#include <set>
#include <string>
#include <vector>

namespace lagrange::config::keys {

using Keys = std::set<std::string>;

inline const Keys kTop = {"name",      "description", "duration", "mode",       "robot",   "initial_state",
                          "reference", "plant",       "actuator", "controller", "metrics", "lockstep",
                          "realtime",  "supervision", "faults",   "sensors",    "compare"};
inline const Keys kRobot = {"preset", "links", "urdf", "gravity", "flexible"};
inline const Keys kUrdf = {"file", "xml", "base_link", "tip_link"};
inline const Keys kLink = {"length", "com", "mass", "inertia"};
inline const Keys kFlexible = {"stiffness", "rotor_inertia", "rate_sensor"};
inline const Keys kInitialState = {"q", "qdot", "motor_q", "motor_qdot"};
inline const Keys kSineReference = {"type", "offset", "amplitude", "frequency", "phase", "alpha"};
inline const Keys kFreeMotionReference = {"type", "initial_q", "initial_qdot"};
inline const Keys kPlant = {"physics_step", "publish_rate", "max_rate"};
inline const Keys kActuator = {"order", "rate", "saturation", "initial_state"};
/// The paper's controllers (a registered type has its own keys, controller/registry.hpp).
inline const Keys kPaperController = {
    "type", "kp", "kd", "a", "b", "initial_filter_state", "stages", "motor_rate", "motor_rate_pole"};
inline const Keys kStage = {"kp", "kd", "a", "b", "initial_filter_state", "initial_zeta"};
inline const Keys kFaults = {"seed", "channels", "receivers"};
inline const Keys kChannelFaults = {"drop", "duplicate", "reorder", "corrupt", "delay", "delay_jitter"};
inline const Keys kReceiverFaults = {"drop"};
inline const Keys kSensors = {"seed", "position", "velocity", "motor"};
inline const Keys kPositionSensor = {"counts_per_revolution", "noise_sigma", "delay"};  // also sensors.motor
inline const Keys kVelocitySensor = {"noise_sigma", "delay"};
inline const Keys kExternalController = {"type", "command", "working_directory"};
inline const Keys kCompare = {"controllers", "sweep"};
inline const Keys kCompareSweep = {"key", "values"};

/// A key as docs/configuration.md's table names it: `row` is the dotted key
/// of its row (list items as [i], map entries by a capital placeholder such
/// as NAME); `inside`, when not empty, a key of a list item or map entry
/// that the row describes in its text.
struct DocumentedKey {
  std::string row;
  std::string inside;
};

/// Every key a scenario file may hold, every section.
std::vector<DocumentedKey> documentedKeys();

}  // namespace lagrange::config::keys
