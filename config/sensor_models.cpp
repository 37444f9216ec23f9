#include "config/sensor_models.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "config/scenario_sections.hpp"

namespace lagrange::config {

namespace {
// Function-local statics: registrations run during static initialisation,
// in any order across translation units.
std::vector<SensorModelKeys>& models() {
  static std::vector<SensorModelKeys> all;
  return all;
}
bool& closed() {
  static bool read = false;
  return read;
}
}  // namespace

void registerSensorModelKeys(SensorModelKeys model) {
  const std::string what = "config::registerSensorModelKeys: sensor model '" + model.model + "'";
  if (closed()) throw std::logic_error(what + " registered after the sensors' keys were first read");
  if (model.keys.empty()) throw std::logic_error(what + " has no key");
  // A sensor's own keys, and every other model's.
  std::set<std::string> taken = keysOf(sections::angleSensorFields());
  for (const std::string& key : keysOf(sections::rateSensorFields())) taken.insert(key);
  for (const SensorModelKeys& m : models()) {
    if (m.model == model.model) throw std::logic_error(what + " is registered twice");
    for (const JointVectorKey& k : m.keys) taken.insert(k.key);
  }
  for (const JointVectorKey& k : model.keys)
    if (!taken.insert(k.key).second) throw std::logic_error(what + ": key '" + k.key + "' is taken");
  models().push_back(std::move(model));
  std::sort(models().begin(), models().end(),
            [](const SensorModelKeys& a, const SensorModelKeys& b) { return a.model < b.model; });
}

const std::vector<SensorModelKeys>& sensorModelKeys() {
  closed() = true;
  return models();
}

}  // namespace lagrange::config
