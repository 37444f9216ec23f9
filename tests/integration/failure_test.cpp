// Processes that die, are interrupted or freeze: the launcher names them and
// keeps the outputs; a frozen controller's silence triggers the plant's
// stale-torque policy and the arm recovers.
#include <gtest/gtest.h>
#include <lcm/lcm.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include "config/scenario.hpp"
#include "controller/cascaded.hpp"
#include "controller/theorem1.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "logger/tracking_metrics.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/rk4.hpp"
#include "support/run_log.hpp"
#include "support/signal_run.hpp"
#include "transport/checksum.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// Runs the default scenario with `options` into `dir` and, once its log
// holds `log_bytes`, freezes the controller (SIGSTOP) for `freeze`.
struct FrozenRun {
  RunResult result;
  bool frozen = false;
};
FrozenRun runFreezingTheController(const std::string& dir, const std::string& options, uintmax_t log_bytes,
                                   std::chrono::milliseconds freeze) {
  std::atomic<bool> done{false};
  FrozenRun out;
  std::thread runner([&] {
    out.result = runScenario(kConfigs + "/rigid_2dof.yaml", dir, options);
    done = true;
  });
  for (int i = 0; i < 2000 && !out.frozen && !done; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!fs::exists(fs::path(dir) / "run.lcm") || fs::file_size(fs::path(dir) / "run.lcm") < log_bytes)
      continue;
    const pid_t pid = findProcess("lagrange-controller", dir);
    if (pid > 0 && kill(pid, SIGSTOP) == 0) {
      std::this_thread::sleep_for(freeze);
      kill(pid, SIGCONT);
      out.frozen = true;
    }
  }
  runner.join();
  return out;
}

// Runs the default scenario for a long time and, once its log holds 100 kB,
// sends `sig` to the process whose argv[0] ends with `process`.
// A dead process: the launcher names it and its signal, stops the rest and
// keeps the log.
TEST(Failure, KilledControllerIsNamedAndTheLogIsKept) {
  const std::string dir = freshDir("kill");
  const SignalledRun run = signalMidRun(dir, kConfigs + "/rigid_2dof.yaml", "lagrange-controller", SIGKILL);
  ASSERT_TRUE(run.signalled);
  EXPECT_EQ(run.result.exit_code, 1) << run.result.output;
  EXPECT_NE(run.result.output.find("process 'controller' was killed by signal 9"), std::string::npos)
      << run.result.output;
  EXPECT_GT(readTruth(dir + "/run.lcm").size(), 10u);  // the log is readable
}

// The plant that stops the simulation (here plant.max_rate) ends its process
// with exit 1; the run is then `diverged`, as in process, with the plant's
// reason -- not `failed`, which a sweep or compare reports as an error
// (found in review: a diverging external controller's rows were failed).
TEST(Failure, APlantThatStopsTheSimulationMakesTheRunDivergedWithItsReason) {
  const std::string dir = freshDir("lockstep-diverged");
  const RunResult r =
      runScenario(kConfigs + "/rigid_2dof.yaml", dir, "-q --set duration=1 --set plant.max_rate=0.5");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto j = readSummary(dir);
  EXPECT_EQ(j["status"], "diverged") << j.dump();
  EXPECT_EQ(j["failure"]["process"], "plant");
  EXPECT_TRUE(j["failure"]["diverged"].get<bool>());
  EXPECT_EQ(j["failure"]["reason"].get<std::string>().rfind("plant: stopped at t = ", 0), 0u)
      << j["failure"].dump();
  EXPECT_NE(j["failure"]["reason"].get<std::string>().find("above plant.max_rate = 0.5"), std::string::npos);
}

// Ctrl-C: every process stops cleanly, the log and the summary are kept.
TEST(Failure, InterruptStopsEveryProcessAndKeepsTheOutputs) {
  const std::string dir = freshDir("interrupt");
  const SignalledRun run = signalMidRun(dir, kConfigs + "/rigid_2dof.yaml", "bin/lagrange", SIGINT);
  const RunResult& r = run.result;
  const bool interrupted = run.signalled;
  ASSERT_TRUE(interrupted);
  EXPECT_EQ(r.exit_code, 130) << r.output;
  const auto j = readSummary(dir);
  EXPECT_EQ(j["status"], "interrupted");
  for (const char* p : {"plant", "controller", "actuator"})
    EXPECT_EQ(j["processes"][p]["state"], "interrupted") << p;
  EXPECT_EQ(findProcess("lagrange-plant", dir), -1) << "a process outlived the launcher";
  const auto truth = readTruth(dir + "/run.lcm");
  EXPECT_GT(truth.size(), 10u);
  EXPECT_EQ(j["tracking"]["samples"].get<size_t>(), truth.size());  // nothing recorded was lost
}

// Issue #46: a controller that takes seconds a sample left the run sitting
// silent (the stall deadline is 10 s a tick). A wait past
// supervision.slow_answer is said on the terminal while it lasts, and
// summary.json has each answerer's median and worst.
TEST(Failure, ASlowAnswerIsSaidWhileItLastsAndSummarised) {
  const std::string dir = freshDir("slow-answer");
  const auto [r, frozen] = runFreezingTheController(dir, "--set duration=3 --set supervision.slow_answer=0.3",
                                                    200000, std::chrono::milliseconds(1200));
  ASSERT_TRUE(frozen) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("lagrange run: the controller (lagrange-controller) has not answered tick "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("(supervision.slow_answer = 0.3 s)"), std::string::npos) << r.output;
  const auto answers = readSummary(dir)["answers"];
  EXPECT_EQ(answers["threshold"], 0.3);
  EXPECT_GE(answers["controller"]["slow"].get<long long>(), 1) << answers.dump();
  EXPECT_GE(answers["controller"]["worst"].get<double>(), 0.8) << answers.dump();
  EXPECT_LT(answers["controller"]["median"].get<double>(), 0.3) << answers.dump();
  EXPECT_GE(answers["controller"]["answered"].get<long long>(), 2900) << answers.dump();
  EXPECT_GE(answers["actuator"]["answered"].get<long long>(), 2900) << answers.dump();
}

// Stale inputs: a controller frozen for 300 ms (SIGSTOP) sends nothing; the
// plant's policy zeroes (or holds) the torque and counts it, the controller
// refuses the positions that aged while it was frozen, and the arm converges
// again afterwards.
class StaleTorquePolicy : public ::testing::TestWithParam<std::string> {};

TEST_P(StaleTorquePolicy, TriggersWhenTheControllerStopsAndTheArmRecovers) {
  const std::string dir = freshDir("stale");
  // Under `zero` every scheduling hiccup longer than max_torque_age (default
  // 2 ms) drops the arm for a period; on a loaded machine those kicks kept it
  // from settling after the freeze (final error 1e-3..2e-2 in some runs).
  // Fresh for 20 ms, a torque rides out hiccups while the 300 ms freeze still
  // zeroes at least 280 periods.
  const std::string age = GetParam() == "zero" ? " --set realtime.max_torque_age=20" : "";
  const auto [r, frozen] = runFreezingTheController(
      dir,
      "-q --mode realtime --set duration=5 --set realtime.stale_torque=" + GetParam() +
          " --set realtime.hold_periods=100" + age,
      600000, std::chrono::milliseconds(300));
  ASSERT_TRUE(frozen);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(dir);
  const auto& plant = j["messages"]["stale"]["plant"];
  const long long zeroed = plant["torque_zeroed"], held = plant["torque_held"];
  const long long stale_positions = j["messages"]["stale"]["controller"]["stale_inputs"];
  std::printf("policy %s: torque held %lld periods, zeroed %lld; controller refused %lld stale positions\n",
              GetParam().c_str(), held, zeroed, stale_positions);
  if (GetParam() == "hold") {
    EXPECT_GE(held, 90);     // held for hold_periods = 100 ...
    EXPECT_GE(zeroed, 100);  // ... then zeroed for the rest of the freeze
  } else {
    EXPECT_EQ(held, 0);
    EXPECT_GE(zeroed, 200);
  }
  // stale_positions is printed, not asserted: whether the resumed controller
  // finds its newest position already too old depends on where in the period
  // it wakes (0 in some runs, 3-19 in others).
  EXPECT_GT(j["tracking"]["max_error"].get<double>(), 1e-2);    // the freeze really disturbed the arm
  EXPECT_LT(j["tracking"]["final_error"].get<double>(), 1e-3);  // and it converged again
}

INSTANTIATE_TEST_SUITE_P(Policies, StaleTorquePolicy, ::testing::Values("zero", "hold"));

}  // namespace
}  // namespace lagrange::testing
