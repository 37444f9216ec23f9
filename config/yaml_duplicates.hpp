#pragma once
/// @file
/// yaml-cpp keeps every entry of a map with a repeated key and answers
/// node[key] with the first, so "kp: 10 ... kp: 500" would silently run with
/// 10. The scenario's tree is walked once, before it is read, and a repeated
/// key is an error naming both lines.

#include <yaml-cpp/yaml.h>

#include <string>

namespace lagrange::config {

/// A tree walk visits at most this many nodes: anchors and aliases share
/// nodes, so a small file can describe an exponentially large tree
/// ("billion laughs"); a scenario has a few hundred.
inline constexpr long kMaxYamlNodes = 1000000;

/// @throws ConfigError "config: SOURCE: duplicate key 'a.b' at line N (first
/// at line M); expected each key once in a map", or when the tree (aliases
/// expanded) has more than kMaxYamlNodes nodes.
void rejectDuplicateKeys(const YAML::Node& root, const std::string& source);

}  // namespace lagrange::config
