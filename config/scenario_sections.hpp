/// @file
/// The readers of the scenario file's sections (config/scenario.cpp calls
/// them in order): each reads one top-level key into the Scenario, checks it
/// against what was read before, and fails with the key's path and what was
/// expected (ConfigError). Internal to lagrange_config.
#pragma once

#include "config/fields.hpp"
#include "config/scenario.hpp"
#include "config/yaml_reader.hpp"

namespace lagrange::config::sections {

// The arm and its task (arm_sections.cpp).
/// `base_dir`: where robot.urdf.file is looked for when relative (the scenario file's folder).
void readRobotSection(MapReader& root, Scenario& s, const std::string& base_dir);
void readInitialStateSection(MapReader& root, Scenario& s);  ///< after robot
void readReferenceSection(MapReader& root, Scenario& s);     ///< after robot and duration
void readPlantSection(MapReader& root, Scenario& s, const std::string& base_dir,
                      bool check_programs);  ///< after duration, mode, robot, sensors

/// name, description, duration, mode: the top level's own keys.
const Fields<Scenario>& headerFields();
const Fields<model::LinkParams>& linkFields();     ///< robot.links[i]
const Fields<FlexibleConfig>& flexibleFields();    ///< robot.flexible
const Fields<UrdfRobotConfig>& urdfFields();       ///< robot.urdf (the document is read by its reader)
const Fields<InitialState>& initialStateFields();  ///< initial_state: q, qdot
const Fields<InitialState>& motorStateFields();    ///< initial_state: motor_q, motor_qdot (robot.flexible)
const Fields<PlantConfig>& plantFields();
/// plant's keys sized by the arm (losses per joint, payload, model error): read after robot.
const Fields<Scenario>& plantArmFields();
/// plant.model_error.
const Fields<model::ModelError>& modelErrorFields();
const Fields<model::ReferenceParams>& referenceFields(model::ReferenceType type);

// What drives it (drive_sections.cpp).
void readActuatorSection(MapReader& root, Scenario& s);  ///< after plant
/// actuator.order, rate (read and checked first); saturation, initial_state.
const Fields<ActuatorConfig>& actuatorChainFields();
const Fields<ActuatorConfig>& actuatorDriveFields();
/// `base_dir`: where a relative controller.command (type external) is looked for.
void readControllerSection(MapReader& root, Scenario& s, const std::string& base_dir,
                           bool check_programs);  ///< after actuator

// How the run is judged and run (run_sections.cpp): the sections described
// field by field (config/fields.hpp), read and written from one description.
const Fields<MetricsConfig>& metricsFields();
const Fields<LockstepConfig>& lockstepFields();
const Fields<RealtimeConfig>& realtimeFields();
const Fields<SupervisionConfig>& supervisionFields();
const Fields<SensorsConfig>& sensorsFields();  ///< sensors' own keys (seed), beside its sensors
const Fields<FaultsConfig>& faultsFields();    ///< faults' own keys (seed), beside channels, receivers
/// sensors.position and sensors.motor; sensors.velocity (no counts_per_revolution).
const Fields<JointSensorConfig>& angleSensorFields();
const Fields<JointSensorConfig>& rateSensorFields();
/// The same, each followed by the registered sensor models' keys
/// (config/sensor_models.hpp): what a sensor's section is read and written with.
const Fields<JointSensorConfig>& angleSensorSection();
const Fields<JointSensorConfig>& rateSensorSection();
const Fields<ChannelFaults>& channelFaultFields();  ///< faults.channels.NAME
/// faults.receivers.PROCESS (Scenario keeps only the number, faults.receiver_drop).
struct ReceiverFaults {
  double drop = 0.0;
};
const Fields<ReceiverFaults>& receiverFaultFields();
void readMetricsSection(MapReader& root, Scenario& s);
void readLockstepSection(MapReader& root, Scenario& s);
void readRealtimeSection(MapReader& root, Scenario& s);
void readSupervisionSection(MapReader& root, Scenario& s);
void readFaultsSection(MapReader& root, Scenario& s);
void readSensorsSection(MapReader& root, Scenario& s);

// What `lagrange compare` runs (compare_section.cpp).
void readCompareSection(MapReader& root, Scenario& s);
const Fields<CompareConfig>& compareFields();       ///< compare: controllers, sweep
const Fields<CompareConfig>& compareSweepFields();  ///< compare.sweep: key, values

}  // namespace lagrange::config::sections
