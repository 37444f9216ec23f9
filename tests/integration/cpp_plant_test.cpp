// The C++ SDK's plant helper (lagrange::sdk::runPlant) in a run: the
// two-link arm of examples/cpp_plant, built outside the tree against the
// installed package, takes the plant's place (plant.type: external) and
// moves as the Python example plant of examples/external_plant does -- the
// same model and RK4, operation for operation --, its run replays bit for
// bit, and a limit it crosses stops the run, said on stderr and in a STATUS
// "failed".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/status_t.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/sweep_files.hpp"

namespace lagrange::testing {
namespace {

const std::string kPlantScenario =
    std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_plant/rigid_2dof_external.yaml";
// One second of the example's scenario: 1001 ticks, the transient included.
const std::string kOneSecond = " -q --set duration=1 --set metrics.convergence_deadline=1";

struct InstalledExample {
  std::string prefix, build;
};

// This build installed into a fresh prefix, and examples/cpp_plant
// configured and built against that prefix, as a user outside the tree would.
InstalledExample buildPlantAgainstTheInstalledPackage() {
  const InstalledExample e{freshDir("cpp-plant-install"), freshDir("cpp-plant-build")};
  const RunResult install = shell("cmake --install " + quote(std::string(LAGRANGE_BIN_DIR) + "/..") +
                                  " --prefix " + quote(e.prefix));
  EXPECT_EQ(install.exit_code, 0) << install.output;
  EXPECT_TRUE(std::filesystem::exists(e.prefix + "/include/lagrange/sdk/external_plant.hpp"));
  const RunResult built = shell(
      "cmake -S " + quote(std::string(LAGRANGE_SOURCE_DIR) + "/examples/cpp_plant") + " -B " +
      quote(e.build) + " -DCMAKE_PREFIX_PATH=" + quote(e.prefix) + " && cmake --build " + quote(e.build));
  EXPECT_EQ(built.exit_code, 0) << built.output;
  return e;
}

// The example's scenario, run by the installed lagrange with the plant command replaced.
RunResult runWithPlant(const InstalledExample& e, const std::string& command, const std::string& out) {
  return shell(quote(e.prefix + "/bin/lagrange") + " run " + quote(kPlantScenario) + kOneSecond + " --set " +
               quote("plant.command=[" + command + "]") + " -o " + quote(out));
}

// (state, message) of every STATUS the plant published, in log order.
std::vector<std::pair<std::string, std::string>> plantStatuses(const std::string& log_path) {
  lcm::LogFile log(log_path, "r");
  std::vector<std::pair<std::string, std::string>> out;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    lagrange::status_t s;
    if (ev->channel == "STATUS" && s.decode(ev->data, 0, ev->datalen) >= 0 && s.process == "plant")
      out.emplace_back(s.state, s.message);
  }
  return out;
}

TEST(CppPlant, ACppPlantBuiltAgainstTheInstalledPackageMovesAsThePythonOneAndStopsAtItsLimits) {
  const InstalledExample example = buildPlantAgainstTheInstalledPackage();
  ASSERT_FALSE(::testing::Test::HasFailure());
  const std::string binary = "\"" + example.build + "/two_link_plant\"";  // YAML, inside the shell's quotes

  const std::string python = freshDir("cpp-plant-python"), cpp = freshDir("cpp-plant-cpp");
  const RunResult python_run = runScenario(kPlantScenario, python, kOneSecond);
  ASSERT_EQ(python_run.exit_code, 0) << python_run.output << readText(python + "/plant.log");
  const RunResult cpp_run = runWithPlant(example, binary, cpp);
  ASSERT_EQ(cpp_run.exit_code, 0) << cpp_run.output << readText(cpp + "/plant.log");
  const auto summary = readSummary(cpp);
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(summary["processes"]["plant"]["state"], "finished");
  EXPECT_EQ(summary["processes"]["plant"]["message"].get<std::string>().rfind("retransmits=", 0), 0u)
      << summary["processes"]["plant"].dump();

  // Both are RK4 with 4 steps a period of the same model, the products
  // grouped alike, on the same torques (lockstep): the same numbers -- 0 rad
  // apart here; 5e-16 with the example compiled with FMA contraction (-mfma
  // -ffp-contract=fast). 1e-12, well within the 1e-6 asked of it, also tells
  // 3 RK4 steps a period from 4 (2.8e-11 apart), which 1e-6 would not.
  const auto a = readTruth(python + "/run.lcm"), b = readTruth(cpp + "/run.lcm");
  ASSERT_EQ(a.size(), 1001u);
  ASSERT_EQ(b.size(), 1001u);
  double worst = 0.0;
  long long worst_tick = -1;
  const size_t common = forCommonTicks(a, b, [&](const TruthSample& x, const TruthSample& y) {
    const double d = (x.q - y.q).cwiseAbs().maxCoeff();
    if (!std::isnan(worst) && !(d <= worst)) {  // a NaN is the worst, and stays
      worst = d;
      worst_tick = x.tick;
    }
    EXPECT_EQ(x.torque_source, y.torque_source) << "tick " << x.tick;
  });
  EXPECT_EQ(common, 1001u);
  EXPECT_LE(worst, 1e-12) << "largest |q_cpp - q_python| " << worst << " rad at tick " << worst_tick;

  // A deterministic plant: its run replays bit for bit, the replay playing
  // actuator and logger to the program named after --.
  const RunResult replay = lagrange("replay " + quote(cpp + "/run.lcm") + " --component plant -- " +
                                    quote(example.build + "/two_link_plant"));
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("plant reproduced all 1001 recorded outputs bit for bit"), std::string::npos)
      << replay.output;

  // Joint 2 leaves [-1.6, -1.4] at tick 12: the plant stops the run, exit 1,
  // naming joint, value, limits and tick on stderr and in STATUS "failed".
  const std::string limited = freshDir("cpp-plant-limits");
  const RunResult stopped =
      runWithPlant(example, binary + ", --position-limit, \"1.9,2.1,-1.6,-1.4\"", limited);
  EXPECT_EQ(stopped.exit_code, 1) << stopped.output;
  const std::string said =
      "joint 2's position -1.39008 rad is outside its limits [-1.6, -1.4] at tick 12 (t = 0.012 s); the "
      "plant stopped the run (its limits)";
  EXPECT_NE(readText(limited + "/plant.log").find("two_link_plant: " + said), std::string::npos)
      << readText(limited + "/plant.log");
  const auto statuses = plantStatuses(limited + "/run.lcm");
  ASSERT_FALSE(statuses.empty());
  EXPECT_EQ(statuses.back(), std::make_pair(std::string("failed"), said));
}

}  // namespace
}  // namespace lagrange::testing
