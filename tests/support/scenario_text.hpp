#pragma once
/// @file
/// Scenario text in unit tests: a file's text, and the error a scenario text
/// (with --set overrides) is refused with.

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "support/configs.hpp"

namespace lagrange::testing {

inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The ConfigError's message, or "(no error)" when the text loads.
inline std::string errorOf(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    config::parseScenario(text, "test.yaml", overrides);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace lagrange::testing
