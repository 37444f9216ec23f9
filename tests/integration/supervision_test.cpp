// Crashes (supervision.*): a controller killed with SIGKILL mid-run is
// restarted with a fresh filter state and the arm converges again -- the
// global stability of the paper, live -- while the plant's stale-torque
// policy holds the arm meanwhile; without restarts, or once they are used
// up, the launcher stops the run and names the dead process. A killed
// logger leaves a log that lagrange report reads, with a warning.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/signal_run.hpp"

namespace lagrange::testing {
namespace {

// About 600 kB of log per simulated second of the realtime rigid_2dof run:
// 1.5 MB is about 2.5 s, well after the first convergence (0.9 s).
constexpr std::uintmax_t kAfterConvergence = 1'500'000;

TEST(Supervision, ARestartedControllerTakesOverAndTheArmConvergesAgain) {
  const std::string dir = freshDir("restart");
  const SignalledRun run = signalMidRun(
      dir, kRigid, "lagrange-controller", SIGKILL,
      "-q --mode realtime --set duration=8 --set supervision.restart=[controller]", kAfterConvergence);
  ASSERT_TRUE(run.signalled);
  ASSERT_EQ(run.result.exit_code, 0) << run.result.output;
  EXPECT_NE(run.result.output.find(
                "process 'controller' was killed by signal 9 (Killed); restarting it (restart 1"),
            std::string::npos)
      << run.result.output;
  const auto j = readSummary(dir);
  EXPECT_EQ(j["supervision"]["restarts"]["controller"], 1) << j["supervision"].dump();
  EXPECT_EQ(j["supervision"]["deaths"][0]["how"], "was killed by signal 9 (Killed)");
  // Meanwhile the plant held the last torque, then applied zero: counted.
  const auto& plant = j["messages"]["stale"]["plant"];
  EXPECT_GT(plant["torque_held"].get<long long>() + plant["torque_zeroed"].get<long long>(), 0)
      << plant.dump();
  // The error left the tolerance after the kill (the arm fell: convergence
  // time after the first convergence) and came back (met, small at the end).
  EXPECT_GT(j["tracking"]["convergence_time"].get<double>(), 1.5) << j["tracking"].dump();
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  EXPECT_LT(j["tracking"]["final_error"].get<double>(), j["tracking"]["tolerance"].get<double>());
  EXPECT_EQ(j["tracking"]["samples"], 8001);  // nothing recorded was lost
}

// Lockstep with an actuator chain: the fresh cascaded controller needs the
// chain state of the tick before its first, which the actuator re-sends while
// the run stalls; without that re-send the run would wait forever.
TEST(Supervision, ARestartedCascadedControllerResumesALockstepRun) {
  const std::string dir = freshDir("restart-chain");
  const SignalledRun run =
      signalMidRun(dir, std::string(LAGRANGE_SOURCE_DIR) + "/configs/chain_m1.yaml", "lagrange-controller",
                   SIGKILL, "-q --set duration=5 --set supervision.restart=[controller]", 2'000'000);
  ASSERT_TRUE(run.signalled);
  ASSERT_EQ(run.result.exit_code, 0) << run.result.output;
  const auto j = readSummary(dir);
  EXPECT_EQ(j["supervision"]["restarts"]["controller"], 1) << j["supervision"].dump();
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  EXPECT_EQ(j["tracking"]["samples"], 5001);
}

// A URDF arm's controller killed mid-run and restarted: the fresh process
// builds the arm from the URDF text in its config and takes over.
TEST(Supervision, ARestartedControllerOfAUrdfArmResumesALockstepRun) {
  const std::string dir = freshDir("restart-panda");
  const SignalledRun run = signalMidRun(
      dir, std::string(LAGRANGE_SOURCE_DIR) + "/configs/panda_theorem1.yaml", "lagrange-controller", SIGKILL,
      "-q --set duration=4 --set supervision.restart=[controller]", 2'000'000);
  ASSERT_TRUE(run.signalled);
  ASSERT_EQ(run.result.exit_code, 0) << run.result.output;
  const auto j = readSummary(dir);
  EXPECT_EQ(j["supervision"]["restarts"]["controller"], 1) << j["supervision"].dump();
  EXPECT_EQ(j["tracking"]["samples"], 4001);
  EXPECT_LT(j["tracking"]["final_error"].get<double>(), j["tracking"]["tolerance"].get<double>())
      << j["tracking"].dump();
}

TEST(Supervision, WithTheRestartsUsedUpTheRunStopsAndNamesTheProcess) {
  const std::string dir = freshDir("restart-none-left");
  const SignalledRun run = signalMidRun(
      dir, kRigid, "lagrange-controller", SIGKILL,
      "-q --set duration=600 --set supervision.restart=[controller] --set supervision.max_restarts=0");
  ASSERT_TRUE(run.signalled);
  EXPECT_EQ(run.result.exit_code, 1) << run.result.output;
  EXPECT_NE(run.result.output.find("process 'controller' was killed by signal 9"), std::string::npos)
      << run.result.output;
  EXPECT_EQ(run.result.output.find("restarting"), std::string::npos) << run.result.output;
  EXPECT_EQ(findProcess("lagrange-plant", dir), -1) << "the others were not stopped";
}

TEST(Supervision, AKilledLoggersLogIsReadAndReportedWithAWarning) {
  const std::string dir = freshDir("kill-logger");
  const SignalledRun run = signalMidRun(dir, kRigid, "lagrange-logger", SIGKILL);
  ASSERT_TRUE(run.signalled);
  EXPECT_EQ(run.result.exit_code, 1) << run.result.output;
  EXPECT_NE(run.result.output.find("process 'logger' was killed by signal 9"), std::string::npos)
      << run.result.output;
  const auto truth = readTruth(dir + "/run.lcm");  // readable up to its last flush
  EXPECT_GT(truth.size(), 10u);
  const RunResult report = lagrange("report " + quote(dir) + " -o " + quote(dir + "/report"));
  EXPECT_EQ(report.exit_code, 0) << report.output;
  EXPECT_NE(report.output.find("plant samples: the run was cut short"), std::string::npos) << report.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/report/tracking_error.png")) << report.output;
}

TEST(Supervision, OnlyTheControllerAndTheActuatorCanBeRestarted) {
  const RunResult r = runScenario(kRigid, freshDir("restart-plant"), "-q --set supervision.restart=[plant]");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("supervision.restart: cannot restart 'plant'; expected controller and/or actuator"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace lagrange::testing
