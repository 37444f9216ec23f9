#pragma once
/// @file
/// A tune's files as the tests read them (docs/tuning.md, "Outputs"):
/// tune.jsonl's lines and tune.json.
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lagrange::testing {

/// DIR/tune.jsonl, a JSON object per line.
inline std::vector<nlohmann::json> tuneLines(const std::string& dir) {
  std::vector<nlohmann::json> out;
  std::ifstream in(dir + "/tune.jsonl");
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(nlohmann::json::parse(line));
  return out;
}

/// DIR/tune.json, and its `result`.
inline nlohmann::json tuneJson(const std::string& dir) {
  return nlohmann::json::parse(std::ifstream(dir + "/tune.json"));
}
inline nlohmann::json tuneResult(const std::string& dir) { return tuneJson(dir).at("result"); }

}  // namespace lagrange::testing
