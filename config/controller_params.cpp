#include "config/controller_params.hpp"

#include <map>
#include <stdexcept>

namespace lagrange::config {

namespace {
// The paper's three, and a controller from outside the project (external).
const std::vector<std::string> kBuiltinTypes = {"theorem1", "cascaded", "flexible", "external"};

// A function-local static: registrations run during static initialisation,
// in any order across translation units.
std::map<std::string, std::vector<ControllerParam>>& registered() {
  static std::map<std::string, std::vector<ControllerParam>> types;
  return types;
}

std::map<std::string, ControllerTraits>& traitsByType() {
  static std::map<std::string, ControllerTraits> types;
  return types;
}
}  // namespace

void registerControllerParams(const std::string& type, std::vector<ControllerParam> params,
                              ControllerTraits traits) {
  for (const auto& t : controllerTypes())
    if (t == type) throw std::logic_error("controller type '" + type + "' is registered twice");
  registered()[type] = std::move(params);
  traitsByType()[type] = traits;
}

ControllerTraits controllerTraits(const std::string& type) {
  const auto it = traitsByType().find(type);
  return it == traitsByType().end() ? ControllerTraits{} : it->second;
}

const std::vector<ControllerParam>* registeredControllerParams(const std::string& type) {
  const auto it = registered().find(type);
  return it == registered().end() ? nullptr : &it->second;
}

std::string controllerTypeList() {
  const std::vector<std::string> types = controllerTypes();
  std::string list;
  for (size_t i = 0; i < types.size(); ++i)
    list += (i == 0 ? "" : i + 1 == types.size() ? " or " : ", ") + types[i];
  return list;
}

std::vector<std::string> controllerTypes() {
  std::vector<std::string> types = kBuiltinTypes;
  for (const auto& [type, params] : registered()) types.push_back(type);
  return types;
}

}  // namespace lagrange::config
