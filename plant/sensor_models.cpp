#include "plant/sensor_models.hpp"

#include <stdexcept>

#include "config/sensor_models.hpp"

namespace lagrange::plant {

namespace {
// A function-local static: registrations run during static initialisation.
std::map<std::string, SensorModel>& models() {
  static std::map<std::string, SensorModel> all;
  return all;
}
}  // namespace

bool registerSensorModel(SensorModel model) {
  if (!model.make)
    throw std::logic_error("plant::registerSensorModel: sensor model '" + model.name + "' has no make");
  config::registerSensorModelKeys({model.name, model.keys});  // refuses a name or key taken
  const std::string name = model.name;
  models().emplace(name, std::move(model));
  return true;
}

std::vector<std::unique_ptr<SensorEffect>> sensorEffects(const config::JointSensorConfig& sensor, int joints,
                                                         uint64_t seed) {
  std::vector<std::unique_ptr<SensorEffect>> effects;
  uint64_t place = 0;
  for (const auto& [name, model] : models()) {
    ++place;
    SensorModelParams params;
    for (const config::JointVectorKey& k : model.keys)
      if (const auto it = sensor.model_params.find(k.key); it != sensor.model_params.end())
        params.emplace(k.key, it->second);
    if (params.empty()) continue;  // config lets a model's keys come all together or not at all
    // Each model its own stream, as each sensor has (scenario_plant.cpp):
    // SplitMix64's second multiplier, so no stream of a sensor is a model's.
    effects.push_back(model.make(params, joints, seed + place * 0xBF58476D1CE4E5B9ULL));
  }
  return effects;
}

}  // namespace lagrange::plant
