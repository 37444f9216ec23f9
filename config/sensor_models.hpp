#pragma once
/// @file
/// The keys of the sensor models registered outside config
/// (plant/sensor_models.hpp): each model adds per-joint keys to every joint
/// sensor's section (sensors.position, sensors.velocity, sensors.motor),
/// which config reads into JointSensorConfig::model_params, checks (a
/// model's keys come all together, or none) and writes back to
/// config.resolved.yaml. A model acts on a sensor whose section gives its keys.

#include <string>
#include <vector>

#include "config/joint_vector_key.hpp"

namespace lagrange::config {

struct SensorModelKeys {
  std::string model;                 ///< its name, for messages
  std::vector<JointVectorKey> keys;  ///< at least one
};

/// From a static initialiser (plant::registerSensorModel does it).
/// @throws std::logic_error for a model without keys, a name taken, a key
///         a joint sensor has of its own or another model took, or a
///         registration after the sensors' keys were first read.
void registerSensorModelKeys(SensorModelKeys model);

/// Every registered model, by name; reading it closes the registrations.
const std::vector<SensorModelKeys>& sensorModelKeys();

}  // namespace lagrange::config
