// The bad-configuration corpus (tests/data/bad_configs/*.yaml): each file
// says on its second line, "# expect: ...", the error `lagrange run` must
// print. Every one is refused with exit 2 and that message, and no process
// is started: the output directory is never even created.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/launch.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;
const std::string kCorpus = std::string(LAGRANGE_SOURCE_DIR) + "/tests/data/bad_configs";

std::string expectedMessage(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  const std::string tag = "# expect: ";
  return line.rfind(tag, 0) == 0 ? line.substr(tag.size()) : "";
}

TEST(BadConfigCorpus, EveryFileIsRefusedWithItsMessageBeforeAnythingStarts) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kCorpus)) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    SCOPED_TRACE(entry.path().filename().string());
    const std::string expected = expectedMessage(entry.path());
    ASSERT_FALSE(expected.empty()) << "no '# expect: ' on the second line";
    const std::string out = freshDir("badconfig");
    const RunResult r = runScenario(entry.path().string(), out, "-q");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("lagrange run: config: " + entry.path().string() + ": " + expected),
              std::string::npos)
        << "expected: " << expected << "\ngot: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << "the output directory was created: something started";
  }
  EXPECT_GE(files, 30);
}

// Bad options are refused the same way: an output directory that cannot be
// created, an override that does not fit the scenario.
TEST(BadConfigCorpus, UnwritableOutputAndBadOverridesAreRefused) {
  const std::string config = std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml";
  const std::string file = freshDir("afile");
  std::ofstream(file) << "a file, not a directory\n";
  for (const std::string& out : {std::string("/proc/lagrange-cannot-be-here"), file + "/sub"}) {
    const RunResult r = runScenario(config, out, "-q");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("output directory '" + out +
                            "' cannot be created or written; expected a writable directory"),
              std::string::npos)
        << r.output;
  }
  const std::string out = freshDir("badset");
  const RunResult r = runScenario(config, out, "-q --set controller.kp=[1,2,3]");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("controller.kp: expected a list of 2 positive numbers"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  const RunResult unknown = runScenario(config, out, "-q --set controller.gain=3");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("controller.gain: unknown key"), std::string::npos) << unknown.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace lagrange::testing
