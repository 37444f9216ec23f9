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

}  // namespace

std::string yamlToJson(const std::string& yaml_text) {
  try {
    // Bytes that are not UTF-8 (a URDF comment in Latin-1) become U+FFFD, not an exception.
    return jsonOfYamlNode(YAML::Load(yaml_text))
               .dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) +
           "\n";
  } catch (const YAML::Exception& e) {
    throw ConfigError(std::string("the scenario is not YAML: ") + e.what());
  }
}

std::string toJson(const Scenario& scenario) { return yamlToJson(toYaml(scenario)); }

}  // namespace lagrange::config
