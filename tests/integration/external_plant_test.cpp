// A plant from outside the project (plant.type external): the two-link arm of
// examples/external_plant/, integrated by RK4 in plain Python behind
// lagrange.external_plant, takes the plant's place over the contract of
// docs/external_programs.md. Its run under the built-in Theorem 1 controller
// matches the ODE plant's, it replays bit for bit (`lagrange replay RUN
// --component plant -- COMMAND`), and the guards a bridge to a real arm
// needs (docs/hardware.md) act: a position limit stops the run naming joint
// and tick, and the watchdog commands zero torque when the answers stop.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

const std::string kExample = std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_plant";
// Two seconds: the arm converges at 0.915 s.
const std::string kShort = "--set duration=2.0 --set metrics.convergence_deadline=2.0";

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The example scenario with the plant's command replaced (python3 -S: no
// site-packages, the package from python/ by the example's own path).
std::string scenarioWith(const std::string& plant_arguments, const std::string& extra_yaml = "") {
  std::string text = readFile(kExample + "/rigid_2dof_external.yaml");
  const std::string from = "command: [python3, two_link_plant.py]";
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("the example scenario's plant command moved");
  text.replace(at, from.size(),
               "command: [python3, -S, \"" + kExample + "/two_link_plant.py\"" + plant_arguments + "]");
  const std::string dir = freshDir("external-plant");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/scenario.yaml";  // its folder: the plant's working directory
  std::ofstream(path) << text << extra_yaml;
  return path;
}

TEST(ExternalPlant, APythonRk4PlantMatchesTheOdePlantAndReplaysBitForBit) {
  const std::string ode = freshDir("external-plant-ode"), python = freshDir("external-plant-python");
  const RunResult builtin =
      runScenario(std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml", ode, kShort + " --quiet");
  ASSERT_EQ(builtin.exit_code, 0) << builtin.output;
  const std::string config = scenarioWith("");
  const RunResult external = runScenario(config, python, kShort + " --quiet");
  ASSERT_EQ(external.exit_code, 0) << external.output;
  // The folder the plant ran in is gone: a log's readers never run its programs.
  std::filesystem::remove_all(std::filesystem::path(config).parent_path());

  // The same trajectory within 1e-3 rad at every tick (ODE's first-order
  // stepper at 2.5e-5 s is within 1 mrad of the exact dynamics; RK4 much closer).
  const std::vector<TruthSample> a = readTruth(ode + "/run.lcm"), b = readTruth(python + "/run.lcm");
  ASSERT_EQ(a.size(), 2001u);
  ASSERT_EQ(b.size(), 2001u);
  double worst = 0.0;
  const size_t common = forCommonTicks(a, b, [&](const TruthSample& x, const TruthSample& y) {
    worst = std::max(worst, (x.q - y.q).cwiseAbs().maxCoeff());
  });
  EXPECT_EQ(common, 2001u);
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(worst, 0.0)
      << "two different integrators cannot agree to the bit: the run was not the external plant's";
  // ... and the same convergence time within 2 %.
  const nlohmann::json sa = readSummary(ode), sb = readSummary(python);
  ASSERT_TRUE(sa["tracking"]["convergence_time"].is_number()) << sa.dump();
  ASSERT_TRUE(sb["tracking"]["convergence_time"].is_number()) << sb.dump();
  const double ta = sa["tracking"]["convergence_time"], tb = sb["tracking"]["convergence_time"];
  EXPECT_LE(std::abs(ta - tb), 0.02 * ta) << ta << " s vs " << tb << " s";
  EXPECT_EQ(sb["status"], "completed");

  // Replay: the program named after -- (never the log's command) reproduces
  // every sample; one that integrates differently is caught at once.
  const std::string command = " --component plant -- python3 -S " + quote(kExample + "/two_link_plant.py");
  const RunResult same = lagrange("replay " + quote(python) + command);
  EXPECT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("plant reproduced all 2001 recorded outputs bit for bit"), std::string::npos)
      << same.output;
  const RunResult other = lagrange("replay " + quote(python) + command + " --substeps 3");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_NE(other.output.find("plant DIVERGED after 2 outputs at tick 1"), std::string::npos) << other.output;
  // Without a command the log's is named, not run.
  const RunResult none = lagrange("replay " + quote(python) + " --component plant");
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("replay runs no program a log names"), std::string::npos) << none.output;
}

TEST(ExternalPlant, APositionLimitStopsTheRunNamingJointValueAndTick) {
  // Joint 1 starts at 2.0 rad and falls towards pi/4: a lower limit of 1.5 rad is crossed early.
  const std::string out = freshDir("external-plant-limit");
  const RunResult r = runScenario(scenarioWith(", --position-limit, \"1.5,3.0,-3.0,3.0\""), out, kShort);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("joint 1's position"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("is outside its limits [1.5, 3]"), std::string::npos) << r.output;
  const nlohmann::json s = readSummary(out);
  EXPECT_EQ(s["status"], "failed") << s.dump();
  EXPECT_EQ(s["failure"]["process"], "plant") << s.dump();
  // The state the log last holds is inside the limit: the plant stopped before publishing the crossing.
  const std::vector<TruthSample> truth = readTruth(out + "/run.lcm");
  ASSERT_FALSE(truth.empty());
  EXPECT_GE(truth.back().q(0), 1.5);
  EXPECT_LT(truth.back().t, 1.0);
}

// A plant that ends early with exit code 0 is no success: the others waited
// for a "finished" that never came.
TEST(ExternalPlant, APlantThatExitsZeroBeforeItsLastTickFailsTheRun) {
  const std::string config = freshDir("external-plant-early") + ".yaml";
  std::ofstream(config) << "extends: " << kExample
                        << "/rigid_2dof_external.yaml\nplant: {type: external, command: [python3, -c, "
                           "\"import sys; sys.exit(0)\"]}\n";
  const std::string out = freshDir("external-plant-early-run");
  const RunResult r = runScenario(config, out, kShort);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("the plant exited with code 0 before the run's last tick"), std::string::npos)
      << r.output;
  const nlohmann::json s = readSummary(out);
  EXPECT_EQ(s["status"], "failed") << s.dump();
  EXPECT_EQ(s["failure"]["process"], "plant") << s.dump();
}

// A plant that hangs: the logger stops the run, and summary.json says why.
TEST(ExternalPlant, AHungPlantLeavesASummarySayingWhy) {
  const std::string config = freshDir("external-plant-hung") + ".yaml";
  std::ofstream(config) << "extends: " << kExample
                        << "/rigid_2dof_external.yaml\nlockstep: {stall_timeout: 0.5}\n"
                           "plant: {type: external, command: [sleep, \"60\"]}\n";
  const std::string out = freshDir("external-plant-hung-run");
  const RunResult r = runScenario(config, out, kShort);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const nlohmann::json s = readSummary(out);
  EXPECT_EQ(s["status"], "failed") << s.dump();
  EXPECT_EQ(s["failure"]["process"], "logger") << s.dump();
  EXPECT_NE(s["failure"]["how"].get<std::string>().find("the plant has not been heard"), std::string::npos)
      << s.dump();
}

// Realtime (by name: it runs alone): the controller stops answering for a
// while, and the plant's watchdog (5 periods) commands zero long before the
// scenario's own stale-torque policy would (hold 2 + 20 periods).
TEST(ExternalPlant, TheWatchdogZeroesTheTorqueWhenAnswersStopRealtime) {
  const std::string dir = freshDir("external-plant-watchdog");
  std::filesystem::create_directories(dir);
  const std::string controller = dir + "/stalling_controller.py";
  // It keeps receiving, and stops publishing its commands at t = 0.3 s; it
  // ends, as any, when the plant says it has finished.
  std::ofstream(controller) << "import sys\n"
                               "sys.path.insert(0, '"
                            << LAGRANGE_SOURCE_DIR
                            << "/python')\n"
                               "import lagrange.external\n"
                               "class Silent(lagrange.external.Controller):\n"
                               "    def _publish_command(self, c):\n"
                               "        if c.header.sim_time < 0.3:\n"
                               "            super()._publish_command(c)\n"
                               "sys.exit(Silent(lambda t, q: [0.0 for _ in q]).serve())\n";
  const std::string config = scenarioWith(", --watchdog-periods, \"5\"");
  std::string text = readFile(config);
  const size_t at = text.find("controller:\n  type: theorem1");
  ASSERT_NE(at, std::string::npos);
  text = text.substr(0, at) + "controller:\n  type: external\n  command: [python3, -S, \"" + controller +
         "\"]\nmetrics: {tolerance: 1.0, convergence_deadline: 1.0}\n";
  text.replace(text.find("mode: lockstep"), 14, "mode: realtime");
  text.replace(text.find("publish_rate: 1000"), 18, "publish_rate: 100");
  std::ofstream(config) << text;
  const std::string out = dir + "/run";
  const RunResult r = runScenario(config, out, "--set duration=1.0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string plant_log = readFile(out + "/plant.log");
  EXPECT_NE(plant_log.find("watchdog: the newest torque"), std::string::npos) << plant_log;
  EXPECT_NE(plant_log.find("commanding zero torque"), std::string::npos) << plant_log;

  // The newest answer the plant can have had is the last ACTUATOR_STATE in the
  // log; five periods later (one more for the period in flight) every torque is zero.
  long long last_answer = -1;
  for (const auto& [channel, tick] : readTicks(out + "/run.lcm"))
    if (channel == "ACTUATOR_STATE") last_answer = std::max(last_answer, tick);
  ASSERT_GE(last_answer, 25) << "the controller answered until t = 0.3 s";
  ASSERT_LT(last_answer, 60) << "the controller was to stop answering at t = 0.3 s";
  const std::vector<TruthSample> truth = readTruth(out + "/run.lcm");
  int zeroed_after = 0;
  for (const TruthSample& s : truth)
    if (s.tick > last_answer + 7) {
      EXPECT_EQ(s.torque_source, int{lagrange::plant_truth_t::TORQUE_ZERO}) << "tick " << s.tick;
      EXPECT_EQ(s.tau.cwiseAbs().maxCoeff(), 0.0) << "tick " << s.tick;
      ++zeroed_after;
    }
  EXPECT_GT(zeroed_after, 20);
  // The policy alone would have held the torque to last_answer + 22: the watchdog zeroed it first.
  for (const TruthSample& s : truth) {
    if (s.tick > last_answer + 7 && s.tick <= last_answer + 22) {
      EXPECT_NE(s.torque_source, int{lagrange::plant_truth_t::TORQUE_HELD}) << "tick " << s.tick;
    }
  }
  const nlohmann::json summary = readSummary(out);
  EXPECT_GT(summary["messages"]["stale"]["plant"]["torque_zeroed"].get<double>(), 20.0) << summary.dump();
  // Its loop is reported like the built-in plant's: SCHED_FIFO from the launcher, every deadline counted.
  const nlohmann::json& loop = summary["timing"]["loops"]["plant"];
  EXPECT_EQ(loop["scheduler"], "fifo:49") << loop.dump();
  EXPECT_EQ(loop["cycles"].get<double>(), 101.0) << loop.dump();
  ASSERT_TRUE(loop["input_age"]["max"].is_number()) << "measured, so not null: " << loop.dump();
  EXPECT_GT(loop["input_age"]["max"].get<double>(), 0.0) << loop.dump();
}

}  // namespace
}  // namespace lagrange::testing
