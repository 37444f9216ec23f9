#include "config/scenario_keys.hpp"

#include "config/scenario_sections.hpp"

namespace lagrange::config::keys {

namespace {
void add(std::vector<DocumentedKey>& out, const std::string& prefix, const Keys& keys,
         const Keys& except = {}) {
  for (const std::string& key : keys)
    if (except.count(key) == 0) out.push_back({prefix + key, ""});
}
void addInside(std::vector<DocumentedKey>& out, const std::string& row, const Keys& keys,
               const Keys& except = {}) {
  for (const std::string& key : keys)
    if (except.count(key) == 0) out.push_back({row, key});
}
template <class T>
void addFields(std::vector<DocumentedKey>& out, const std::string& prefix, const Fields<T>& fields) {
  add(out, prefix, keysOf(fields));
}
}  // namespace

std::vector<DocumentedKey> documentedKeys() {
  std::vector<DocumentedKey> out;
  // Sections are not rows: their keys are.
  add(out, "", kTop,
      {"robot", "initial_state", "reference", "plant", "actuator", "controller", "metrics", "lockstep",
       "realtime", "supervision", "faults", "sensors", "compare"});
  add(out, "robot.", kRobot, {"flexible", "urdf"});
  addInside(out, "robot.links", kLink);
  add(out, "robot.urdf.", kUrdf);
  add(out, "robot.flexible.", kFlexible);
  add(out, "initial_state.", kInitialState);
  add(out, "reference.", kSineReference);
  add(out, "reference.", kFreeMotionReference, {"type"});
  add(out, "plant.", kPlant);
  add(out, "actuator.", kActuator);
  add(out, "controller.", kPaperController);
  add(out, "controller.", kExternalController, {"type"});
  addInside(out, "controller.stages", kStage, {"initial_filter_state", "initial_zeta"});
  out.push_back({"controller.stages[i].initial_filter_state", ""});
  out.push_back({"controller.stages[i].initial_zeta", ""});
  addFields(out, "metrics.", sections::metricsFields());
  addFields(out, "lockstep.", sections::lockstepFields());
  addFields(out, "realtime.", sections::realtimeFields());
  addFields(out, "supervision.", sections::supervisionFields());
  add(out, "faults.", kFaults, {"channels", "receivers"});
  addInside(out, "faults.channels.NAME", kChannelFaults);
  out.push_back({"faults.receivers.PROCESS.drop", ""});
  add(out, "sensors.", kSensors, {"position", "velocity", "motor"});
  add(out, "sensors.position.", kPositionSensor);
  add(out, "sensors.velocity.", kVelocitySensor);
  add(out, "sensors.motor.", kPositionSensor);
  add(out, "compare.", kCompare, {"controllers", "sweep"});
  out.push_back({"compare.controllers.TYPE", ""});
  add(out, "compare.sweep.", kCompareSweep);
  return out;
}

}  // namespace lagrange::config::keys
