#include "config/scenario_json.hpp"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

namespace lagrange::config {

namespace {

// A plain (unquoted) scalar as YAML 1.2's core schema reads it.
nlohmann::ordered_json jsonOfPlainScalar(const std::string& text) {
  if (text == "true" || text == "True" || text == "TRUE") return true;
  if (text == "false" || text == "False" || text == "FALSE") return false;
  if (text.empty() || text == "~" || text == "null" || text == "Null" || text == "NULL") return nullptr;
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long long integer = std::strtoll(begin, &end, 10);
  if (errno == 0 && end != begin && *end == '\0') return integer;
  errno = 0;
  const double number = std::strtod(begin, &end);
  // Finite numbers only: JSON has no infinity or NaN (a scenario holds none).
  if (errno == 0 && end != begin && *end == '\0' && std::isfinite(number) &&
      text.find_first_of("xXnN") == std::string::npos)
    return number;
  return text;
}

nlohmann::ordered_json jsonOfYamlNode(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      nlohmann::ordered_json object = nlohmann::ordered_json::object();
      for (const auto& entry : node) object[entry.first.as<std::string>()] = jsonOfYamlNode(entry.second);
      return object;
    }
    case YAML::NodeType::Sequence: {
      nlohmann::ordered_json array = nlohmann::ordered_json::array();
      for (const auto& item : node) array.push_back(jsonOfYamlNode(item));
      return array;
    }
    case YAML::NodeType::Scalar:
      // A quoted scalar's tag is "!": a string whatever it reads like.
      return node.Tag() == "!" ? nlohmann::ordered_json(node.Scalar()) : jsonOfPlainScalar(node.Scalar());
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      break;
  }
  return nullptr;
}

nlohmann::ordered_json parsedYaml(const std::string& yaml_text) {
  try {
    return jsonOfYamlNode(YAML::Load(yaml_text));
  } catch (const YAML::Exception& e) {
    throw ConfigError(std::string("the scenario is not YAML: ") + e.what());
  }
}

// Bytes that are not UTF-8 (a URDF comment in Latin-1) become U+FFFD, not an exception.
std::string dumped(const nlohmann::ordered_json& j) {
  return j.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace

std::string yamlToJson(const std::string& yaml_text) { return dumped(parsedYaml(yaml_text)); }

std::string toJson(const Scenario& scenario) {
  nlohmann::ordered_json j = parsedYaml(toYaml(scenario));
  // The emitter writes a string that reads as a number ("20", an argument;
  // a scenario named 2026) unquoted, and YAML would read it back as one: the
  // strings the scenario holds go in as the strings they are.
  if (j.is_object()) {
    if (j.contains("name")) j["name"] = scenario.name;
    if (j.contains("controller") && j["controller"].is_object() && j["controller"].contains("command"))
      j["controller"]["command"] = scenario.controller.command;
    if (j.contains("plant") && j["plant"].is_object() && j["plant"].contains("command"))
      j["plant"]["command"] = scenario.plant.command;
  }
  return dumped(j);
}

}  // namespace lagrange::config
