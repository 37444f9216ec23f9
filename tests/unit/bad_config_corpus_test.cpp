// The bad-configuration corpus (tests/data/bad_configs/*.yaml) in process:
// each file is refused, by the scenario's loading or the plant's build check
// -- what `lagrange run` does before anything starts -- with the message its
// second line states ("# expect: ..."). The integration test
// (BadConfigCorpus.*) runs the same files through the command; this one is
// what the sanitizer pass keeps (a process a file is 99 instrumented starts).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "config/scenario.hpp"
#include "plant/scenario_plant.hpp"
#include "support/configs.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// This program registers the seams' test-only kinds (tests/unit/
// controller_registry_test.cpp, robot_kind_seam_test.cpp), which a message
// listing the registered names includes; `lagrange run` has none of them.
std::string withoutTestKinds(std::string message) {
  message = std::regex_replace(message, std::regex(R"(, ([a-z0-9_]+) or test_[a-z0-9_]+)"), " or $1");
  return std::regex_replace(message, std::regex(R"( \(or a kind built into this program: [^)]*\))"), "");
}

TEST(BadConfigCorpusInProcess, EveryFileIsRefusedWithItsMessage) {
  const fs::path corpus = kBadConfigs;
  int files = 0;
  for (const auto& entry : fs::directory_iterator(corpus)) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    const std::string path = entry.path().string();
    SCOPED_TRACE(entry.path().filename().string());
    const std::string expected = expectedMessageOf(entry.path());
    ASSERT_FALSE(expected.empty()) << "no '# expect: ' on the second line";
    try {
      const config::Scenario s = config::loadScenario(path);
      if (!s.plant.external()) plant::checkPlantBuilds(s);
      ADD_FAILURE() << "accepted; expected: " << expected;
    } catch (const std::exception& e) {
      EXPECT_NE(withoutTestKinds(e.what()).find("config: " + path + ": " + expected), std::string::npos)
          << "expected: " << expected << "\ngot: " << e.what();
    }
  }
  EXPECT_GE(files, 30);
}

}  // namespace
}  // namespace lagrange::testing
