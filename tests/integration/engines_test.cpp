// The two physics engines side by side (plant.engine, plant/physics_engine.hpp):
// a MuJoCo run is as deterministic as an ODE one -- lockstep equals in-process
// bit for bit, and its log replays through the plant -- and on the shipped
// configs the two engines reach the same verdict at the same time.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/wait.hpp"

namespace lagrange::testing {
namespace {

// Joint damping and friction too: MuJoCo's constraint solver starts each step
// from the last one's answer, which a replay must rebuild in the same order.
constexpr const char* kMujocoPelican =
    "-q --set duration=2 --set plant.engine=mujoco --set plant.physics_step=1e-3 "
    "--set 'plant.joint_damping=[0.3, 0.05]' --set 'plant.joint_friction=[0.2, 0.05]'";

TEST(Engines, AMujocoRunIsTheSameInLockstepAndInProcessAndItsLogReplaysThroughThePlant) {
  const std::string config = kConfigs + "/rigid_2dof.yaml";
  const std::string lockstep = freshDir("mujoco-lockstep"), inproc = freshDir("mujoco-inproc");
  const RunResult a = runScenario(config, lockstep, std::string(kMujocoPelican) + " --mode lockstep");
  const RunResult b = runScenario(config, inproc, std::string(kMujocoPelican) + " --mode inproc");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto ta = readTruth(lockstep + "/run.lcm"), tb = readTruth(inproc + "/run.lcm");
  ASSERT_EQ(ta.size(), 2001u);
  ASSERT_EQ(tb.size(), 2001u);
  for (size_t k = 0; k < ta.size(); ++k) {
    ASSERT_EQ(ta[k].q, tb[k].q) << "tick " << k;
    ASSERT_EQ(ta[k].energy, tb[k].energy) << "tick " << k;
  }
  EXPECT_EQ(readCommands(lockstep + "/run.lcm"), readCommands(inproc + "/run.lcm"));
  // The run says which engine it ran on, where a user reads it back.
  const auto j = readSummary(lockstep);
  EXPECT_EQ(j["plant"]["engine"], "mujoco") << j["plant"].dump();
  EXPECT_EQ(j["plant"]["mujoco_integrator"], "rk4") << j["plant"].dump();
  EXPECT_NE(slurp(lockstep + "/config.resolved.yaml").find("engine: mujoco"), std::string::npos);
  // Replay rebuilds the engine the log's scenario names: the plant's
  // answers, every tick, bit for bit (on ODE they would differ at once).
  const RunResult replay = lagrange("replay " + quote(lockstep + "/run.lcm") + " --component plant");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("plant reproduced all 2001"), std::string::npos) << replay.output;
}

// A shipped config and the physics step MuJoCo runs it at: the control
// rate's own where the motion allows; the flexible arm's rotors turn at
// 1 900 rad/s in its first millisecond, past a quarter turn per 1 ms step.
struct EnginePair {
  const char* config;
  const char* mujoco_step;
};
void PrintTo(const EnginePair& p, std::ostream* os) { *os << p.config; }

class EngineAgreement : public ::testing::TestWithParam<EnginePair> {};

// The verdict does not depend on the engine: ODE at the config's own step
// and MuJoCo at its own both meet the metric, and the convergence times
// agree within 1 % (measured: within 0.1 % on every shipped config).
TEST_P(EngineAgreement, BothEnginesMeetTheMetricAndConvergeWithinOnePercent) {
  const std::string config = kConfigs + "/" + GetParam().config + ".yaml";
  const std::string ode = freshDir("engine-ode"), mujoco = freshDir("engine-mujoco");
  const RunResult a = runScenario(config, ode, "-q --mode inproc");
  const RunResult b =
      runScenario(config, mujoco,
                  std::string("-q --mode inproc --set plant.engine=mujoco --set plant.physics_step=") +
                      GetParam().mujoco_step);
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto ja = readSummary(ode)["tracking"], jb = readSummary(mujoco)["tracking"];
  EXPECT_TRUE(ja["met"].get<bool>()) << ja.dump();
  EXPECT_TRUE(jb["met"].get<bool>()) << jb.dump();
  const double ta = ja["convergence_time"].get<double>(), tb = jb["convergence_time"].get<double>();
  RecordProperty("convergence_ode", std::to_string(ta));
  RecordProperty("convergence_mujoco", std::to_string(tb));
  EXPECT_NEAR(tb, ta, 0.01 * ta) << "ODE " << ta << " s, MuJoCo " << tb << " s";
}

INSTANTIATE_TEST_SUITE_P(Shipped, EngineAgreement,
                         ::testing::Values(EnginePair{"rigid_2dof", "1e-3"},
                                           EnginePair{"panda_theorem1", "1e-3"},
                                           EnginePair{"chain_m2", "1e-3"},
                                           EnginePair{"flexible_2dof", "1e-4"}));

}  // namespace
}  // namespace lagrange::testing
