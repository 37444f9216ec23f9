// The project's version is written in one place, CMakeLists.txt's
// project(lagrange VERSION ...): `lagrange --version` prints it and every
// summary.json carries it (logger/summary.cpp), so a result names the
// programs that made it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

std::string cmakeProjectVersion() {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/CMakeLists.txt");
  std::stringstream text;
  text << in.rdbuf();
  std::smatch m;
  const std::string s = text.str();
  return std::regex_search(s, m, std::regex(R"(project\(lagrange VERSION ([0-9]+\.[0-9]+\.[0-9]+))"))
             ? m[1].str()
             : "";
}

TEST(Version, TheFrontEndAndEverySummaryNameCMakeListsVersion) {
  const std::string version = cmakeProjectVersion();
  ASSERT_FALSE(version.empty()) << "no project(lagrange VERSION x.y.z) in CMakeLists.txt";
  const RunResult printed = lagrange("--version");
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  EXPECT_EQ(printed.output, "lagrange " + version + "\n");
  // In process and from the logger process: the same summary, two programs.
  for (const std::string mode : {"inproc", "lockstep"}) {
    const std::string out = freshDir("version-" + mode);
    const RunResult run =
        runScenario(kConfigs + "/rigid_2dof.yaml", out, "-q --mode " + mode + " --set duration=0.05");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(readSummary(out).value("lagrange_version", ""), version) << mode;
  }
}

}  // namespace
}  // namespace lagrange::testing
