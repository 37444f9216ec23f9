#pragma once
/// @file
/// The shipped scenario files (configs/), for tests that run each of them.

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace lagrange::testing {

inline const std::string kConfigs = std::string(LAGRANGE_SOURCE_DIR) + "/configs";

/// The stem of every configs/*.yaml, sorted.
inline std::vector<std::string> shippedConfigs() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kConfigs))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace lagrange::testing
