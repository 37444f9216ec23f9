#pragma once
/// The resolved scenario as JSON, for programs that cannot read YAML (an
/// external controller written against the standard library only): the same
/// tree as config.resolved.yaml (config::toYaml), its numbers as JSON
/// numbers, true/false as booleans, null as null, every other scalar (and
/// every quoted one) as a string; keys in the YAML's order.

#include <string>

#include "config/scenario.hpp"

namespace lagrange::config {

/// The scenario's resolved YAML as a JSON document (indented, one key a line).
std::string toJson(const Scenario& scenario);

/// The same for any YAML text (a log's SCENARIO). @throws ConfigError when
/// the text is not YAML.
std::string yamlToJson(const std::string& yaml_text);

}  // namespace lagrange::config
