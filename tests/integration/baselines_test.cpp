// The baselines (docs/baselines.md) as a user runs them: named in
// controller.type, known to every process of the stock programs, the same
// trajectory in lockstep and in-process bit for bit, and the report saying
// which claims come with them.
#include <gtest/gtest.h>

#include <fstream>

#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

// The Pelican tracking the default scenario's sinusoid, PD+ on differenced
// positions at 1 kHz, its gains those of configs/rigid_2dof.yaml's stage.
constexpr const char* kPdPlusDifferenced = R"(name: pd_plus_differenced_pelican
duration: 3.0
mode: lockstep
robot:
  preset: pelican
initial_state:
  q: [0.5, -0.5]
  qdot: [0.0, 0.0]
reference:
  type: sine
  offset: [0.1, 0.2]
  amplitude: [0.5, 0.3]
  frequency: [2.0, 3.0]
plant:
  physics_step: 1.0e-4
  publish_rate: 1000
controller:
  type: pd_plus_differenced
  kp: [150.0, 10.0]
  kd: [15.0, 1.0]
metrics:
  tolerance: 1.0e-3
  convergence_deadline: 2.0
)";

TEST(Baselines, PdPlusDifferencedTracksTheSameInLockstepAndInProcess) {
  const std::string config = freshDir("baseline-config") + ".yaml";
  std::ofstream(config) << kPdPlusDifferenced;
  const std::string lockstep = freshDir("baseline-lockstep"), inproc = freshDir("baseline-inproc");
  const RunResult a = runScenario(config, lockstep, "--mode lockstep");
  const RunResult b = runScenario(config, inproc, "-q --mode inproc");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  // No stability condition is claimed for it, and the run says so.
  EXPECT_NE(a.output.find("no stability condition is known for controller type 'pd_plus_differenced'"),
            std::string::npos)
      << a.output;
  const auto ta = readTruth(lockstep + "/run.lcm"), tb = readTruth(inproc + "/run.lcm");
  ASSERT_EQ(ta.size(), 3001u);
  ASSERT_EQ(tb.size(), 3001u);
  for (size_t k = 0; k < ta.size(); ++k) ASSERT_EQ(ta[k].q, tb[k].q) << "tick " << k;
  EXPECT_EQ(readCommands(lockstep + "/run.lcm"), readCommands(inproc + "/run.lcm"));
  const auto j = readSummary(lockstep);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  EXPECT_EQ(j["controller"]["type"], "pd_plus_differenced") << j["controller"].dump();
  // Its log replays through the controller exactly.
  const RunResult replay = lagrange("replay " + quote(lockstep + "/run.lcm") + " --component controller");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("reproduced all 3001 recorded outputs"), std::string::npos) << replay.output;
}

}  // namespace
}  // namespace lagrange::testing
