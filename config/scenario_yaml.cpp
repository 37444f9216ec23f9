/// @file
/// toYaml: the resolved scenario, every default filled in
/// (config.resolved.yaml, the SCENARIO message).

#include <yaml-cpp/yaml.h>

#include "config/controller_params.hpp"
#include "config/robot_kinds.hpp"
#include "config/scenario.hpp"
#include "config/scenario_sections.hpp"

namespace lagrange::config {

namespace {
using field::writeVector;
}  // namespace

std::string toYaml(const Scenario& s) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  writeFields(out, s, sections::headerFields());

  out << YAML::Key << "robot" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "gravity" << YAML::Value << s.robot.gravity;
  if (s.registered_robot) {
    out << YAML::Key << s.registered_robot->key << YAML::Value;
    robotKindSection(s.registered_robot->key)->write(out, s.registered_robot->settings);
  } else if (s.urdf) {
    out << YAML::Key << "urdf" << YAML::Value << YAML::BeginMap;
    writeFields(out, *s.urdf, sections::urdfFields());
    out << YAML::EndMap;
  } else {
    out << YAML::Key << "links" << YAML::Value << YAML::BeginSeq;
    for (const auto& l : s.robot.links) {
      out << YAML::Flow << YAML::BeginMap;
      writeFields(out, l, sections::linkFields());
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  if (s.flexible) {
    out << YAML::Key << "flexible" << YAML::Value << YAML::BeginMap;
    writeFields(out, *s.flexible, sections::flexibleFields());
    out << YAML::EndMap;
  }
  out << YAML::EndMap;

  out << YAML::Key << "initial_state" << YAML::Value << YAML::BeginMap;
  writeFields(out, s.initial_state, sections::initialStateFields());
  if (s.flexible) writeFields(out, s.initial_state, sections::motorStateFields());
  out << YAML::EndMap;

  out << YAML::Key << "reference" << YAML::Value << YAML::BeginMap;
  writeFields(out, s.reference, sections::referenceFields(s.reference.type));
  out << YAML::EndMap;

  out << YAML::Key << "plant" << YAML::Value << YAML::BeginMap;
  if (s.plant.external()) {  // the simulated plant's keys do not apply (and are refused)
    out << YAML::Key << "type" << YAML::Value << s.plant.type;
    out << YAML::Key << "publish_rate" << YAML::Value << s.plant.publish_rate;
    out << YAML::Key << "command" << YAML::Value << YAML::Flow << s.plant.command;
    out << YAML::Key << "working_directory" << YAML::Value << s.plant.working_directory;
  } else {  // type simulated, the default, left out: a resolved file stays as it was
    writeFields(out, s.plant, sections::plantFields());
    writeFields(out, s, sections::plantArmFields());
  }
  out << YAML::EndMap;

  out << YAML::Key << "actuator" << YAML::Value << YAML::BeginMap;
  writeFields(out, s.actuator, sections::actuatorChainFields());
  writeFields(out, s.actuator, sections::actuatorDriveFields());
  out << YAML::EndMap;

  out << YAML::Key << "controller" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "type" << YAML::Value << s.controller.type;
  for (const auto& [key, value] : s.controller.params) writeVector(out, key, value);
  if (s.controller.type == "external") {
    out << YAML::Key << "command" << YAML::Value << YAML::Flow << s.controller.command;
    out << YAML::Key << "working_directory" << YAML::Value << s.controller.working_directory;
  } else if (const ControllerRegistration* registration = controllerRegistration(s.controller.type);
             registration && registration->section.write) {
    registration->section.write(out, s);
  }
  out << YAML::EndMap;

  auto section = [&out](const char* key, const auto& value, const auto& fields) {
    out << YAML::Key << key << YAML::Value << YAML::BeginMap;
    writeFields(out, value, fields);
    out << YAML::EndMap;
  };
  section("metrics", s.metrics, sections::metricsFields());
  section("lockstep", s.lockstep, sections::lockstepFields());
  section("realtime", s.realtime, sections::realtimeFields());
  section("supervision", s.supervision, sections::supervisionFields());

  out << YAML::Key << "faults" << YAML::Value << YAML::BeginMap;
  writeFields(out, s.faults, sections::faultsFields());
  out << YAML::Key << "channels" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, rule] : s.faults.channels) {
    out << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginMap;
    writeFields(out, rule, sections::channelFaultFields());
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  out << YAML::Key << "receivers" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, drop] : s.faults.receiver_drop) {
    out << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginMap;
    writeFields(out, sections::ReceiverFaults{drop}, sections::receiverFaultFields());
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  out << YAML::EndMap;

  if (s.sensors) {
    out << YAML::Key << "sensors" << YAML::Value << YAML::BeginMap;
    writeFields(out, *s.sensors, sections::sensorsFields());
    const auto sensor = [&](const char* name, const JointSensorConfig& c, const auto& fields) {
      out << YAML::Key << name << YAML::Value << YAML::BeginMap;
      writeFields(out, c, fields);
      out << YAML::EndMap;
    };
    sensor("position", s.sensors->position, sections::angleSensorSection());
    if (s.sensors->velocity) sensor("velocity", *s.sensors->velocity, sections::rateSensorSection());
    if (s.sensors->motor) sensor("motor", *s.sensors->motor, sections::angleSensorSection());
    out << YAML::EndMap;
  }

  if (s.compare) {
    out << YAML::Key << "compare" << YAML::Value << YAML::BeginMap;
    writeFields(out, *s.compare, sections::compareFields());
    out << YAML::EndMap;
  }

  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace lagrange::config
