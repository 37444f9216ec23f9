// The run's clock and ticks are the logger's, not a participant's: a plant
// from outside (tests/data/hostile_plant.py, properly signed, lying in what
// it says) that stamps half the time, publishes past the run's end, says
// "finished" early, or skips to the last tick. Each lie is seen to happen
// (the plant's own counts, the logger's refusals), then refused or turned
// into a failed run named as the plant -- never `completed` and met.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

// The example's lockstep scenario at 0.2 s (201 ticks) with the lying plant.
std::string lyingPlant(const std::string& name, const std::string& lie, const std::string& extra = "") {
  const std::string example = std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_plant";
  const std::string config = freshDir(name) + ".yaml";
  std::ofstream(config) << "extends: " << example << "/rigid_2dof_external.yaml\n"
                        << "duration: 0.2\nlockstep: {stall_timeout: 1}\n"
                        << extra << "plant: {type: external, command: [python3, -S, \"" << LAGRANGE_SOURCE_DIR
                        << "/tests/data/hostile_plant.py\", \"" << example << "\", " << lie << "]}\n";
  return config;
}

long long notRecorded(const nlohmann::json& summary, const std::string& channel) {
  const nlohmann::json& counts = summary["log"]["not_recorded"];
  return counts.contains(channel) && counts[channel].contains("outside_run")
             ? counts[channel]["outside_run"].get<long long>()
             : 0;
}

TEST(HostilePlant, ATimeStampedAtHalfItsTicksIsRefusedAndSaidNotMeasured) {
  const std::string out = freshDir("hostile-half-time-run");
  const RunResult r = runScenario(lyingPlant("hostile-half-time", "half_time"), out, "");
  // The lie was told and refused: the logger says so on the terminal, and
  // counts each refused sample as invalid.
  EXPECT_NE(r.output.find("the logger refuses PLANT_TRUTH from the plant: sim_time 0.000500 s is not its "
                          "tick's time (tick 1"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.exit_code, 0) << r.output;  // the plant, never confirmed, stalls: the run fails
  const nlohmann::json s = readSummary(out);
  EXPECT_GT(s["messages"]["PLANT_TRUTH"]["rejected_by_reason"]["invalid"].get<long long>(), 0)
      << s["messages"];
  EXPECT_NE(s["status"], "completed");
  EXPECT_NE(s["verdict"]["tracking"], "met") << s["verdict"].dump(2);
  // No sample past tick 0 was measured on the plant's clock.
  EXPECT_LE(s["tracking"]["samples"].get<long long>(), 1) << s["tracking"].dump(2);
}

TEST(HostilePlant, TicksPastTheRunsEndAreNeitherRecordedNorCounted) {
  const std::string out = freshDir("hostile-past-end-run");
  const RunResult r =
      runScenario(lyingPlant("hostile-past-end", "past_end, \"20\"", "mode: realtime\n"), out, "");
  const nlohmann::json s = readSummary(out);
  // The plant published 20 ticks past the end (realtime, over UDP: a
  // datagram may be lost); the logger recorded none of them.
  EXPECT_GE(notRecorded(s, "PLANT_TRUTH"), 10) << s["log"].dump(2);
  EXPECT_LE(notRecorded(s, "PLANT_TRUTH"), 20) << s["log"].dump(2);
  EXPECT_LE(notRecorded(s, "PLANT_POSITION"), 20) << s["log"].dump(2);
  EXPECT_LE(s["tracking"]["samples"].get<long long>(), 201) << s["tracking"].dump(2);
  EXPECT_EQ(r.exit_code, 0) << r.output;  // its ticks 0 to 200 are the run's
  for (const auto& [channel, tick] : readTicks(out + "/run.lcm"))
    EXPECT_LE(tick, 200) << channel << ": a tick past the run's end was recorded";
}

TEST(HostilePlant, APlantThatSaysFinishedEarlyFailsTheRunNamedAsThePlant) {
  const std::string out = freshDir("hostile-finish-early-run");
  const RunResult r = runScenario(lyingPlant("hostile-finish-early", "finish_early, \"50\""), out, "");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("the plant said \"finished\" at tick 50, before the run's last tick 200"),
            std::string::npos)
      << r.output;
  const nlohmann::json s = readSummary(out);
  EXPECT_EQ(s["processes"]["plant"]["last_tick"], 50) << s["processes"].dump(2);  // the lie, as told
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["failure"]["process"], "plant");
  EXPECT_EQ(s["verdict"]["tracking"], "NOT met") << s["verdict"].dump(2);
}

TEST(HostilePlant, APlantThatSkipsToTheLastTickFailsTheRunNamedAsThePlant) {
  const std::string out = freshDir("hostile-jump-run");
  const RunResult r = runScenario(lyingPlant("hostile-jump", "jump, \"50\""), out, "--check met");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("the plant said \"finished\" at the run's last tick, but the log lacks PLANT_TRUTH "
                          "for 149 of the run's ticks"),
            std::string::npos)
      << r.output;
  const nlohmann::json s = readSummary(out);
  EXPECT_EQ(s["log"]["missing_ticks"]["PLANT_TRUTH"], 149) << s["log"].dump(2);  // the skip happened
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["failure"]["process"], "plant");
  EXPECT_EQ(s["verdict"]["met"], false);
  bool named = false;
  for (const auto& reason : s["verdict"]["reasons"]) named = named || reason["kind"] == "missing_ticks";
  EXPECT_TRUE(named) << s["verdict"].dump(2);
}

// Exit 0 without a word at tick 50: the logger hears the plant no more and
// stops the run (4 x stall_timeout) -- the plant is named, not the logger.
TEST(HostilePlant, APlantThatVanishesWithExitZeroIsNamedNotTheLogger) {
  const std::string out = freshDir("hostile-vanish-run");
  const RunResult r = runScenario(lyingPlant("hostile-vanish", "vanish, \"50\""), out, "");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("the plant exited with code 0 before the run's last tick"), std::string::npos)
      << r.output;
  const nlohmann::json s = readSummary(out);
  EXPECT_EQ(s["failure"]["process"], "plant") << s.dump(2);
  EXPECT_EQ(s["status"], "failed");
  EXPECT_LT(s["tracking"]["samples"].get<long long>(), 201);  // it did end early
}

// A plant's own bad number is blamed on the plant: a finite q of 1e308 (the
// controller would turn it into an infinite torque, and be named), and a
// NaN in PLANT_TRUTH only (which only the logger reads).
TEST(HostilePlant, APlantsBadNumbersAreRefusedAndSaidAsThePlants) {
  for (const std::string lie : {"huge", "nan_truth"}) {
    const std::string out = freshDir("hostile-" + lie + "-run");
    const RunResult r = runScenario(lyingPlant("hostile-" + lie, lie + ", \"50\""), out, "");
    const std::string said = lie == "huge" ? "the logger refuses PLANT_TRUTH from the plant: value 1e+308"
                                           : "the logger refuses PLANT_TRUTH from the plant: non-finite";
    EXPECT_NE(r.output.find(said), std::string::npos) << r.output;
    EXPECT_EQ(r.exit_code, 1) << r.output;
    const nlohmann::json s = readSummary(out);
    EXPECT_GT(s["messages"]["PLANT_TRUTH"]["rejected_by_reason"]["invalid"].get<long long>(), 0) << lie;
    EXPECT_EQ(s["failure"]["process"], "plant") << lie;
    // The controller was never handed the plant's number to answer with an infinite command.
    EXPECT_EQ(s["messages"]["CONTROL_COMMAND"]["rejected_by_reason"]["invalid"], 0) << lie;
  }
}

}  // namespace
}  // namespace lagrange::testing
