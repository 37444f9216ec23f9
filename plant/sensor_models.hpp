#pragma once
/// @file
/// The sensor-model seam: a model is an effect on a joint sensor's value
/// (plant::SensorEffect) with per-joint keys in every sensor's section
/// (sensors.position, sensors.velocity, sensors.motor). A new model is one
/// file with its effect and one registration:
///
///     const bool registered = lagrange::plant::registerSensorModel(
///         {"offset", {{"offset", false, "added to the value [rad, or rad/s]"}},
///          [](const SensorModelParams& p, int joints, uint64_t seed) {
///            return std::make_unique<Offset>(p.at("offset")); }});
///
/// Its keys are then read, checked and written back by config, and every
/// wiring (lockstep, realtime, in-process) and replay apply it: each sensor
/// whose section gives the keys applies the effect after its delay and before
/// its noise and quantisation. Every program of a run that reads the
/// scenario must be built with the file (as for a controller,
/// docs/extending.md, "Adding a sensor model").

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "config/joint_vector_key.hpp"
#include "config/scenario.hpp"
#include "plant/joint_sensor.hpp"

namespace lagrange::plant {

/// A model's keys as one sensor's section gives them: key -> per-joint values.
using SensorModelParams = std::map<std::string, Eigen::VectorXd>;

struct SensorModel {
  std::string name;                          ///< for messages; models act in name order
  std::vector<config::JointVectorKey> keys;  ///< all given, or none
  /// Its effect on one sensor of `joints` joints; `seed` is the effect's own
  /// (drawn from sensors.seed, the sensor and the model's place), for a
  /// model that draws.
  std::function<std::unique_ptr<SensorEffect>(const SensorModelParams& params, int joints, uint64_t seed)>
      make;
};

/// Registers a model (its keys with config, its effect here). Returns true,
/// for a namespace-scope initialiser. @throws std::logic_error for a name or
/// key taken, or a model without keys or `make`.
bool registerSensorModel(SensorModel model);

/// The effects of the models whose keys `sensor` gives, in name order, for
/// a sensor of `joints` joints drawing from `seed`.
std::vector<std::unique_ptr<SensorEffect>> sensorEffects(const config::JointSensorConfig& sensor, int joints,
                                                         uint64_t seed);

}  // namespace lagrange::plant
