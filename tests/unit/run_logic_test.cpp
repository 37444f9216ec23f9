// `lagrange run`'s own logic, without processes: the result block and the
// metrics --check finds missed (tools/run/run_outcome.hpp), the launch rules
// (tools/run/launch_rules.hpp) and the progress pipe's reader
// (tools/run/progress_reader.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <string>

#include "logger/error_line.hpp"
#include "tools/run/launch_rules.hpp"
#include "tools/run/progress_reader.hpp"
#include "tools/run/run_outcome.hpp"

namespace lagrange::tools {
namespace {

nlohmann::json summaryOf(bool met, nlohmann::json convergence_time) {
  return {{"scenario", "rigid_2dof"},
          {"status", "completed"},
          {"tracking",
           {{"final_error", 1.25e-5},
            {"tolerance", 1e-3},
            {"convergence_time", convergence_time},
            {"convergence_deadline", 0.5},
            {"met", met}}},
          {"torque", {{"max_abs", 61.5}}},
          {"gains", {{"condition_holds", true}, {"margin", 0.0421}}},
          {"timing", {{"sim_time", 3.0}, {"wall_time", 1.5}, {"realtime_factor", 2.0}}}};
}

TEST(RunLogic, TheResultBlockSaysWhatTheSummarySays) {
  const std::string met = resultText(summaryOf(true, 0.25));
  EXPECT_NE(met.find("scenario rigid_2dof: completed -- tracking met\n"), std::string::npos) << met;
  EXPECT_NE(met.find("final tracking error  1.250e-05 rad (tolerance 1.0e-03)"), std::string::npos) << met;
  EXPECT_NE(met.find("convergence time      0.250 s (deadline 0.500 s: met)"), std::string::npos) << met;
  EXPECT_NE(met.find("max |torque|          61.500 N m"), std::string::npos) << met;
  EXPECT_NE(met.find("gain condition        holds (continuous time; margin 0.0421)"), std::string::npos)
      << met;
  EXPECT_NE(met.find("sim 3.00 s in 1.50 s wall (2.0x real time)"), std::string::npos) << met;

  EXPECT_NE(resultText(summaryOf(false, 0.75)).find("(deadline 0.500 s: MISSED)"), std::string::npos);
  EXPECT_NE(resultText(summaryOf(false, nullptr)).find("convergence time      never"), std::string::npos);

  nlohmann::json unchecked = summaryOf(true, 0.25);
  unchecked["gains"] = {{"checked", false}, {"why", "a baseline has no stated condition"}};
  EXPECT_NE(
      resultText(unchecked).find("gain condition        not checked (a baseline has no stated condition)"),
      std::string::npos);
  nlohmann::json violated = summaryOf(true, 0.25);
  violated["gains"]["condition_holds"] = false;
  EXPECT_NE(resultText(violated).find("VIOLATED"), std::string::npos);

  nlohmann::json torn = summaryOf(true, 0.25);
  torn.erase("torque");
  EXPECT_THROW(resultText(torn), nlohmann::json::exception) << "a missing field is not printed as zero";
}

TEST(RunLogic, CheckNamesEveryMissedMetricWithItsValue) {
  EXPECT_TRUE(missedMetrics(summaryOf(true, 0.25)).empty());

  nlohmann::json chain = summaryOf(false, nullptr);
  chain["tracking"]["chain"] = {
      {{"stage", 1}, {"tolerance", 0.01}, {"convergence_time", 0.3}, {"final_error", 1e-4}},
      {{"stage", 2}, {"tolerance", 0.01}, {"convergence_time", 0.9}, {"final_error", 2e-3}},
      {{"stage", 3}, {"tolerance", 0.01}, {"convergence_time", nullptr}, {"final_error", 5.0}}};
  const auto missed = missedMetrics(chain);
  ASSERT_EQ(missed.size(), 4u)
      << "the tracking error and stages 2 and 3 (stage 1 converged in time), then why";
  EXPECT_EQ(missed[0].rfind("metric MISSED: ||q~|| below 0.001 rad by t = 0.5 s", 0), 0u) << missed[0];
  EXPECT_NE(missed[0].find("converged never, final error 1.25e-05 rad"), std::string::npos) << missed[0];
  EXPECT_NE(missed[1].find("||xit_2|| below 0.01 by t = 0.5 s: converged 0.900000 s"), std::string::npos)
      << missed[1];
  EXPECT_NE(missed[2].find("||xit_3||"), std::string::npos);
  EXPECT_NE(missed[2].find("converged never, final error 5"), std::string::npos) << missed[2];
  EXPECT_EQ(missed[3].rfind("why: ||q~|| did not stay below", 0), 0u)
      << "the verdict's reason: " << missed[3];
}

TEST(RunLogic, APartialLaunchNeedsTheNetworkTheUrlAndTheKey) {
  RunOptions opt;
  EXPECT_EQ(checkProcesses(opt), "");
  EXPECT_TRUE(runsHere(opt, "plant"));
  opt.processes = {"plant", "camera"};
  EXPECT_NE(checkProcesses(opt).find("unknown process 'camera'"), std::string::npos);
  opt.processes = {"plant"};
  EXPECT_TRUE(runsHere(opt, "plant"));
  EXPECT_FALSE(runsHere(opt, "logger"));
  EXPECT_NE(checkProcesses(opt).find("add --no-netns"), std::string::npos);
  opt.private_netns = false;
  EXPECT_NE(checkProcesses(opt).find("--lcm-url"), std::string::npos);
  opt.lcm_url = "udpm://239.255.76.67:7667?ttl=1";
  EXPECT_NE(checkProcesses(opt).find("--key-file"), std::string::npos);
  opt.key_file = "/tmp/k";
  EXPECT_EQ(checkProcesses(opt), "");
  opt.processes = kProcesses;
  opt.private_netns = true;
  EXPECT_EQ(checkProcesses(opt), "") << "all four here is a whole run";
}

TEST(RunLogic, HostsOfOneRunAgreeOnItsIdentity) {
  const int64_t id = sharedRunId("udpm://239.255.76.67:7667?ttl=1", "name: a\n");
  EXPECT_EQ(id, sharedRunId("udpm://239.255.76.67:7667?ttl=1", "name: a\n"));
  // Pinned: hosts running different versions of this project must still agree.
  EXPECT_EQ(id, 2843483059056066161LL);
  EXPECT_GT(id, 0);
  EXPECT_EQ(id & 1, 1) << "never 0, which means any run";
  EXPECT_NE(id, sharedRunId("udpm://239.255.76.67:7668?ttl=1", "name: a\n"));
  EXPECT_NE(id, sharedRunId("udpm://239.255.76.67:7667?ttl=1", "name: b\n"));
}

TEST(RunLogic, ADeadProcessIsRestartedWhileItHasRestartsLeft) {
  config::SupervisionConfig policy;
  policy.restart = {"controller"};
  policy.max_restarts = 2;
  nlohmann::json supervision = supervisionRecord(policy);
  EXPECT_TRUE(mayRestart(policy, supervision, "controller", "killed by signal 9"));
  EXPECT_TRUE(mayRestart(policy, supervision, "controller", "exit 1"));
  EXPECT_FALSE(mayRestart(policy, supervision, "controller", "exit 1")) << "two restarts used up";
  EXPECT_FALSE(mayRestart(policy, supervision, "actuator", "exit 1")) << "not named in supervision.restart";
  EXPECT_EQ(supervision["restarts"]["controller"], 2);
  ASSERT_EQ(supervision["deaths"].size(), 4u);
  EXPECT_EQ(supervision["deaths"][0]["how"], "killed by signal 9");
  EXPECT_EQ(supervision["deaths"][2]["restarted"], false);
  EXPECT_EQ(supervision["deaths"][3]["process"], "actuator");
  EXPECT_EQ(supervision["restart"], nlohmann::json::array({"controller"}));
}

// A plant that exited 0 before the run was recorded whole ended it short:
// how, from the logger's summary (the plant's last word, the ticks missing).
TEST(RunLogic, APlantThatEndedTheRunShortIsToldHow) {
  nlohmann::json s = {{"status", "interrupted"},
                      {"mode", "lockstep"},
                      {"processes", {{"plant", {{"state", "finished"}, {"last_tick", 50}}}}},
                      {"log", {{"missing_ticks", {{"PLANT_TRUTH", 0}}}}}};
  EXPECT_EQ(plantEndedEarly(s, 200),
            "said \"finished\" at tick 50, before the run's last tick 200, and exited with code 0");
  s["processes"]["plant"]["last_tick"] = 200;
  s["log"]["missing_ticks"]["PLANT_TRUTH"] = 149;
  EXPECT_EQ(plantEndedEarly(s, 200),
            "said \"finished\" at the run's last tick, but the log lacks PLANT_TRUTH for 149 of the run's "
            "ticks (skipped, or never confirmed by the logger), and exited with code 0");
  s["mode"] = "realtime";  // a last sample lost on the way: no plant's fault
  EXPECT_EQ(plantEndedEarly(s, 200), "");
  s["processes"]["plant"]["state"] = "running";
  EXPECT_EQ(plantEndedEarly(s, 200).rfind("exited with code 0 before the run's last tick", 0), 0u);
  s["status"] = "completed";
  EXPECT_EQ(plantEndedEarly(s, 200), "");
  // No summary of this run (a logger that failed before writing it, e.g. a
  // full disk after the plant's end): nothing says the plant did it.
  EXPECT_EQ(plantEndedEarly(nullptr, 200), "");
}

TEST(RunLogic, TheProgressPipeGivesTheNewestLineAndTheLoggersLastWord) {
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  ProgressReader reader(fds[0]);
  EXPECT_FALSE(reader.wait(0).has_value()) << "nothing written yet";
  const std::string lines = "0.5 0.1\n1.0 0.01\n1.5 0.0";  // the last line is not ended yet
  ASSERT_EQ(write(fds[1], lines.data(), lines.size()), static_cast<ssize_t>(lines.size()));
  auto newest = reader.wait(1000);
  ASSERT_TRUE(newest.has_value());
  EXPECT_EQ(newest->first, 1.0);
  EXPECT_EQ(newest->second, 0.01);
  const std::string rest = "01\n" + std::string(logger::kLoggerErrorPrefix) + "disk full\nnot numbers\n";
  ASSERT_EQ(write(fds[1], rest.data(), rest.size()), static_cast<ssize_t>(rest.size()));
  newest = reader.wait(1000);
  ASSERT_TRUE(newest.has_value());
  EXPECT_EQ(newest->first, 1.5);
  EXPECT_EQ(newest->second, 0.001) << "a line split over two reads is read whole";
  EXPECT_EQ(reader.loggerError(), "disk full");
  close(fds[1]);
  EXPECT_FALSE(reader.wait(100).has_value()) << "end of the pipe";
  close(fds[0]);
}

}  // namespace
}  // namespace lagrange::tools
