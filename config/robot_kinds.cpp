#include "config/robot_kinds.hpp"

#include <map>
#include <stdexcept>

namespace lagrange::config {

namespace {
// A function-local static: registrations run during static initialisation.
std::map<std::string, RobotKindSection>& kinds() {
  static std::map<std::string, RobotKindSection> all;
  return all;
}
// robot.* keys config reads itself (config/arm_sections.cpp).
bool ownKey(const std::string& key) {
  return key == "preset" || key == "links" || key == "urdf" || key == "gravity" || key == "flexible";
}
}  // namespace

void registerRobotKindSection(RobotKindSection kind) {
  const std::string what = "config::registerRobotKindSection: robot." + kind.key;
  if (ownKey(kind.key) || kinds().count(kind.key) != 0) throw std::logic_error(what + " is taken");
  if (!kind.read || !kind.model || !kind.write)
    throw std::logic_error(what + " lacks a read, model or write");
  const std::string key = kind.key;
  kinds().emplace(key, std::move(kind));
}

const RobotKindSection* robotKindSection(const std::string& key) {
  const auto it = kinds().find(key);
  return it == kinds().end() ? nullptr : &it->second;
}

std::vector<std::string> robotKindKeys() {
  std::vector<std::string> keys;
  for (const auto& [key, kind] : kinds()) keys.push_back(key);
  return keys;
}

}  // namespace lagrange::config
