// What a user reads first is what happened: runs a user met, each ending in
// a block whose first line says it (logger/verdict.hpp decides it, the
// result block, compare and sweep read it). A 3-link chain whose gains
// satisfy eq. (12) but whose loop at 200 Hz is unstable flies off, and its
// block says "NOT met", the divergence and the rate that would suffice; a
// plant that takes 1.5 s over one step in lockstep is named while it lasts
// and counted in answers.plant.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

// The 5-link chain's first three links and gains (configs/rigid_5link.yaml):
// eq. (12) holds; at 200 Hz the sampled loop is unstable.
std::string threeLinkChain() {
  const std::string path = freshDir("verdict-3link") + ".yaml";
  std::ofstream(path) << R"(name: my_3link
duration: 2.0
mode: inproc
robot:
  gravity: 9.81
  links:
    - {length: 0.3, com: 0.15, mass: 3.0, inertia: 0.0225}
    - {length: 0.3, com: 0.15, mass: 2.5, inertia: 0.01875}
    - {length: 0.3, com: 0.15, mass: 2.0, inertia: 0.015}
initial_state: {q: [1.0, -1.0, 0.5], qdot: [0.0, 0.5, -0.5]}
reference: {type: sine, offset: 0.2, amplitude: 0.1, frequency: [1.0, 1.2, 1.4], phase: [0.0, 0.5, 1.0]}
plant: {physics_step: 1.0e-4, publish_rate: 200}
controller: {type: theorem1, kp: [200.0, 120.0, 80.0], kd: [20.0, 15.0, 10.0], a: 50.0, b: 100.0,
             initial_filter_state: bumpless}
metrics: {tolerance: 1.0e-3, convergence_deadline: 1.5}
)";
  return path;
}

TEST(RunVerdict, ADivergingChainEndsSayingNotMetTheDivergenceAndTheRate) {
  const std::string out = freshDir("verdict-3link-run");
  const RunResult r = runScenario(threeLinkChain(), out, "");
  const nlohmann::json s = readSummary(out);
  ASSERT_EQ(s["gains"]["sampled_data"]["verdict"], "unstable") << s["gains"].dump(2);
  ASSERT_TRUE(s["gains"]["condition_holds"].get<bool>()) << "eq. (12) holds: only the sampled loop fails";
  const nlohmann::json& v = s["verdict"];
  EXPECT_EQ(v["tracking"], "NOT met") << v.dump(2);
  // The block's first line: the status, then the verdict with its reasons.
  const size_t at = r.output.find("scenario my_3link: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string first = r.output.substr(at, r.output.find('\n', at) - at);
  EXPECT_NE(first.find("tracking NOT met: "), std::string::npos) << first;
  EXPECT_NE(first.find("diverged"), std::string::npos) << first;
  EXPECT_NE(first.find("the sampled loop at 200 Hz is unstable (linearised check;"), std::string::npos)
      << first;
  EXPECT_NE(first.find("would suffice: plant.publish_rate"), std::string::npos) << first;
  EXPECT_NE(r.output.find("(continuous time; margin"), std::string::npos) << r.output;
  // --check met fails it, naming the reasons.
  const RunResult checked = runScenario(threeLinkChain(), freshDir("verdict-3link-check"), "-q --check met");
  EXPECT_EQ(checked.exit_code, 3) << checked.output;
  EXPECT_NE(checked.output.find("why: diverged"), std::string::npos) << checked.output;
}

// Lockstep, over LCM: the plant (a program from outside) takes 1.5 s over
// one step. The logger names it while it lasts and counts it; the verdict
// warns of it though the run met its metric.
TEST(RunVerdict, APlantSlowerThanSlowAnswerIsNamedWhileItLastsAndCounted) {
  const std::string example = std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_plant";
  const std::string config = freshDir("verdict-slow-plant") + ".yaml";
  std::ofstream(config) << "extends: " << example
                        << "/rigid_2dof_external.yaml\n"
                           "plant: {type: external, command: [python3, -S, \""
                        << LAGRANGE_SOURCE_DIR << "/tests/data/slow_step_plant.py\", \"" << example
                        << "\", \"40\", \"1.5\"]}\n"
                           "supervision: {slow_answer: 0.5}\n";
  const std::string out = freshDir("verdict-slow-plant-run");
  const RunResult r = runScenario(config, out, "--set duration=0.2 --set metrics.convergence_deadline=0.2");
  EXPECT_NE(r.output.find("the plant (python3 -S "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("has not answered tick 39"), std::string::npos) << r.output;
  const nlohmann::json s = readSummary(out);
  const nlohmann::json& plant = s["answers"]["plant"];
  EXPECT_EQ(plant["slow"], 1) << s["answers"].dump(2);
  // The logger hears the question a little after the plant does (its loop
  // wakes every 20 ms; a sanitizer build later still): 1.5 s less that.
  EXPECT_GT(plant["worst"].get<double>(), 1.0);
  EXPECT_EQ(plant["worst_tick"], 39);
  bool warned = false;
  for (const auto& w : s["verdict"]["warnings"]) warned = warned || w["kind"] == "slow_answers";
  EXPECT_TRUE(warned) << s["verdict"].dump(2);
  EXPECT_NE(r.output.find("warnings:"), std::string::npos) << r.output;
}

// Realtime, over LCM: the plant (a program from outside) needs 2 ms of work
// in every 1 ms period. The block's first line names the plant's timing and
// what its torque was, not only plant.log.
TEST(RunVerdict, APlantThatCannotHoldItsRateInRealtimeIsTheFirstLinesReason) {
  const std::string example = std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_plant";
  const std::string config = freshDir("verdict-late-plant") + ".yaml";
  std::ofstream(config) << "extends: " << example
                        << "/rigid_2dof_external.yaml\n"
                           "mode: realtime\n"
                           "plant: {type: external, command: [python3, -S, \""
                        << LAGRANGE_SOURCE_DIR << "/tests/data/slow_step_plant.py\", \"" << example
                        << "\", \"1\", \"0.002\", every]}\n";
  const std::string out = freshDir("verdict-late-plant-run");
  const RunResult r = runScenario(config, out, "--set duration=0.3 --set metrics.convergence_deadline=0.3");
  const nlohmann::json s = readSummary(out);
  // The fault happened: the plant's own loop statistics say it was late.
  const nlohmann::json& plant = s["timing"]["loops"]["plant"];
  ASSERT_LT(plant["on_time_fraction"].get<double>(), 0.5) << plant.dump(2);
  EXPECT_LT(plant["achieved_rate"].get<double>(), 900.0) << plant.dump(2);
  // The verdict's first reason is the plant's timing, and says its torque.
  EXPECT_EQ(s["verdict"]["tracking"], "NOT met") << s["verdict"].dump(2);
  ASSERT_FALSE(s["verdict"]["reasons"].empty()) << s["verdict"].dump(2);
  const nlohmann::json& first = s["verdict"]["reasons"][0];
  EXPECT_EQ(first["kind"], "timing") << s["verdict"].dump(2);
  const std::string why = first["text"];
  EXPECT_EQ(why.rfind("the plant's loop was on time on ", 0), 0u) << why;
  EXPECT_NE(why.find("Hz of 1000"), std::string::npos) << why;
  const nlohmann::json& stale = s["messages"]["stale"]["plant"];
  if (stale["torque_held"].get<long long>() + stale["torque_zeroed"].get<long long>() == 0) {
    EXPECT_NE(why.find("torque was fresh on every period"), std::string::npos) << why;
  } else {
    bool named = false;
    for (const auto& reason : s["verdict"]["reasons"]) named = named || reason["kind"] == "stale_torque";
    for (const auto& warning : s["verdict"]["warnings"]) named = named || warning["kind"] == "stale_torque";
    EXPECT_TRUE(named) << s["verdict"].dump(2);
  }
  // ... and the block's first line is that reason.
  const std::string line = "scenario rigid_2dof_external: completed -- tracking NOT met: " + why;
  EXPECT_NE(r.output.find(line), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lagrange::testing
