#pragma once
/// @file
/// The shipped scenario files (configs/) and the golden logs, for the tests
/// that read them (defined once: the tests compile as unity batches).

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace lagrange::testing {

inline const std::string kConfigs = std::string(LAGRANGE_SOURCE_DIR) + "/configs";
/// The default scenario, the one most tests run.
inline const std::string kRigid = kConfigs + "/rigid_2dof.yaml";
/// The golden logs (tests/data/golden/, scripts/record_golden.sh), with the
/// trailing slash, and the default scenario's lockstep one.
inline const std::string kGoldenDir = std::string(LAGRANGE_SOURCE_DIR) + "/tests/data/golden/";
inline const std::string kGoldenRigidLockstep = kGoldenDir + "rigid_2dof_lockstep.lcm";

/// The bad-configuration corpus (tests/data/bad_configs/*.yaml).
inline const std::string kBadConfigs = std::string(LAGRANGE_SOURCE_DIR) + "/tests/data/bad_configs";

/// What a corpus file says `lagrange run` must print, on its second line
/// ("# expect: ..."); "" when it says nothing.
inline std::string expectedMessageOf(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  const std::string tag = "# expect: ";
  return line.rfind(tag, 0) == 0 ? line.substr(tag.size()) : "";
}

/// The stem of every configs/*.yaml, sorted.
inline std::vector<std::string> shippedConfigs() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kConfigs))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace lagrange::testing
