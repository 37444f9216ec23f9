#include "config/physics_engines.hpp"

#include <algorithm>
#include <stdexcept>

namespace lagrange::config {

namespace {
std::vector<std::string>& keys() {
  static std::vector<std::string> all = {"ode", "mujoco"};
  return all;
}
}  // namespace

void registerPhysicsEngineKey(const std::string& key) {
  if (std::find(keys().begin(), keys().end(), key) != keys().end())
    throw std::logic_error("config: the physics engine '" + key + "' is registered already");
  keys().push_back(key);
}

std::vector<std::string> physicsEngineKeys() { return keys(); }

}  // namespace lagrange::config
