#include "config/controller_params.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace lagrange::config {

namespace {
// A controller from outside the project: known to config itself, listed
// after the paper's three (registered at 0..2) and before the rest.
constexpr const char* kExternal = "external";
constexpr int kExternalListing = 30;

// A function-local static: registrations run during static initialisation,
// in any order across translation units.
std::map<std::string, ControllerRegistration>& registered() {
  static std::map<std::string, ControllerRegistration> types;
  return types;
}
}  // namespace

void registerControllerSection(ControllerRegistration registration) {
  const std::string type = registration.type;
  if (type == kExternal || registered().count(type) != 0)
    throw std::logic_error("controller type '" + type + "' is registered twice");
  if (static_cast<bool>(registration.section.read) != static_cast<bool>(registration.section.write))
    throw std::logic_error("controller type '" + type +
                           "' registers a section reader without a writer, or the converse");
  registered().emplace(type, std::move(registration));
}

const ControllerRegistration* controllerRegistration(const std::string& type) {
  const auto it = registered().find(type);
  return it == registered().end() ? nullptr : &it->second;
}

ControllerTraits controllerTraits(const std::string& type) {
  const ControllerRegistration* r = controllerRegistration(type);
  return r ? r->traits : ControllerTraits{};
}

std::string controllerTypeList() {
  const std::vector<std::string> types = controllerTypes();
  std::string list;
  for (size_t i = 0; i < types.size(); ++i)
    list += (i == 0 ? "" : i + 1 == types.size() ? " or " : ", ") + types[i];
  return list;
}

std::vector<std::string> controllerTypes() {
  std::vector<std::pair<int, std::string>> listed = {{kExternalListing, kExternal}};
  for (const auto& [type, registration] : registered()) listed.emplace_back(registration.listing, type);
  std::sort(listed.begin(), listed.end());
  std::vector<std::string> types;
  for (const auto& entry : listed) types.push_back(entry.second);
  return types;
}

}  // namespace lagrange::config
