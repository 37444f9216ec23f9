// Seeded fault injection (config faults.*) on every channel:
// - lockstep (rigid, integrator chain, flexible joints) with 5 % drops, duplicates, reordering and corrupted
// bytes yields the trajectory
//   of the fault-free run bit for bit, with every sample in the log: the
//   plant re-sends positions nobody answered and samples the logger has not
//   confirmed, the controller and actuator answer re-sent ticks from their
//   caches, the actuator re-sends its state while the run stalls, and
//   duplicates and late datagrams are rejected by sequence number, corrupted
//   ones by the MAC (then re-sent like lost ones);
// - lockstep with 5 % lost by each receiver alone (faults.receivers) keeps a
//   complete log: the plant re-sends what the logger has not confirmed;
// - realtime with 1 % drops and up to 2 ms of random delay converges within
//   twice the nominal time, and the counters add up: what the plant published,
//   minus what was dropped, is what the controller received or rejected.
//   Three such hops make the loop up to ~7 periods late, past the shipped
//   realtime.max_torque_age of 2: the plant applies those late torques under
//   the "hold" policy (the newest one, held flat) and counts them. Holding the
//   last fresh torque instead, as it first did, let the arm fall away.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

const char* kChannels[] = {"PLANT_POSITION", "PLANT_TRUTH", "CONTROL_COMMAND", "ACTUATOR_STATE", "STATUS"};

// The run under faults is the fault-free one: all 1001 samples, each bit for
// bit, and its log replays exactly through every component.
void expectTheFaultFreeRun(const std::string& clean_dir, const std::string& faulty_dir) {
  const auto a = readTruth(clean_dir + "/run.lcm"), b = readTruth(faulty_dir + "/run.lcm");
  ASSERT_EQ(a.size(), 1001u);
  ASSERT_EQ(b.size(), 1001u) << "samples missing from the log under faults";
  size_t identical = 0;
  forCommonTicks(
      a, b, [&](const TruthSample& x, const TruthSample& y) { identical += x.q == y.q && x.qdot == y.qdot; });
  EXPECT_EQ(identical, 1001u);
  for (const std::string component : {"controller", "actuator", "plant"}) {
    const RunResult replay =
        lagrange("replay " + quote(faulty_dir + "/run.lcm") + " --component " + component);
    EXPECT_EQ(replay.exit_code, 0) << component << ": " << replay.output;
    EXPECT_NE(replay.output.find("reproduced all 1001 recorded outputs"), std::string::npos) << replay.output;
  }
}

// One lockstep run per wiring: the rigid arm (Theorem 1), an integrator chain
// (ACTUATOR_STATE also feeds the controller), the flexible-joint arm
// (PLANT_MOTOR with the motor rates) and a URDF arm (seven joints).
class LockstepUnderFaults : public ::testing::TestWithParam<std::string> {};

TEST_P(LockstepUnderFaults, DropsDuplicatesReorderingAndCorruptionLeaveTheTrajectoryBitIdentical) {
  const std::string config = std::string(LAGRANGE_SOURCE_DIR) + "/configs/" + GetParam() + ".yaml";
  const std::string clean = freshDir("faults-clean"), faulty = freshDir("faults-lockstep");
  ASSERT_EQ(runScenario(config, clean, "-q --set duration=1").exit_code, 0);
  const RunResult r =
      runScenario(config, faulty,
                  "-q --set duration=1 --set lockstep.retransmit_timeout=0.01 --set "
                  "'faults.channels.all={drop: 0.05, duplicate: 0.05, reorder: 0.05, corrupt: 0.05}'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(faulty);
  std::vector<std::string> channels(std::begin(kChannels), std::end(kChannels));
  if (GetParam().rfind("flexible", 0) == 0) channels.push_back("PLANT_MOTOR");
  for (const std::string& channel : channels) {  // the faults happened ...
    const auto& injected = j["messages"][channel]["injected"];
    EXPECT_GT(injected["dropped"].get<long long>(), 0) << channel << injected.dump();
    EXPECT_GT(injected["duplicated"].get<long long>(), 0) << channel << injected.dump();
    EXPECT_GT(injected["reordered"].get<long long>(), 0) << channel << injected.dump();
    EXPECT_GT(injected["corrupted"].get<long long>(), 0) << channel << injected.dump();
  }
  // A flipped byte is caught by the MAC, before any decoding: nothing
  // corrupted reaches the decoder or the checksum.
  const auto& reasons = j["messages"]["PLANT_POSITION"]["rejected_by_reason"];
  EXPECT_GT(reasons["unauthenticated"].get<long long>(), 0) << reasons.dump();
  EXPECT_EQ(reasons["corrupt"].get<long long>() + reasons["undecodable"].get<long long>(), 0)
      << reasons.dump();
  EXPECT_GT(j["messages"]["PLANT_POSITION"]["rejected_by_reason"]["old_or_repeated"].get<long long>(), 0);
  // ... and nothing changed: every message of every tick logged (STATUS
  // aside), the fault-free trajectory, corrupted copies and all replayed.
  EXPECT_EQ(j["tracking"]["samples"], 1001);
  for (const std::string& channel : channels) {
    if (channel != "STATUS") {
      EXPECT_EQ(j["log"]["missing_ticks"][channel], 0) << channel << j["log"].dump();
    }
  }
  expectTheFaultFreeRun(clean, faulty);
}

INSTANTIATE_TEST_SUITE_P(Faults, LockstepUnderFaults,
                         ::testing::Values("rigid_2dof", "chain_m2", "flexible_2dof", "panda_theorem1"));

// Loss that only one receiver sees (faults.receivers), as on a real network
// where one host misses a datagram the others got: every process loses 5 %
// of what reaches it, the logger included. The plant re-sends every tick the
// logger has not confirmed (all of its messages), the controller and the
// actuator answer those again from what they sent, and the log is complete.
TEST(Faults, LossSeenByOneReceiverAloneIsSentAgainUntilTheLogIsComplete) {
  const std::string config = std::string(LAGRANGE_SOURCE_DIR) + "/configs/chain_m2.yaml";
  const std::string clean = freshDir("faults-clean"), lossy = freshDir("faults-receivers");
  ASSERT_EQ(runScenario(config, clean, "-q --set duration=1").exit_code, 0);
  const RunResult r = runScenario(config, lossy,
                                  "-q --set duration=1 --set lockstep.retransmit_timeout=0.01 --set "
                                  "'faults.receivers={plant: {drop: 0.05}, controller: {drop: 0.05}, "
                                  "actuator: {drop: 0.05}, logger: {drop: 0.05}}'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(lossy);
  // The losses happened, at the logger on every per-tick channel ...
  const auto& at_logger = j["processes"]["logger"]["channels"];
  for (const char* channel : {"PLANT_POSITION", "PLANT_TRUTH", "CONTROL_COMMAND", "ACTUATOR_STATE"}) {
    EXPECT_GT(at_logger[channel]["injected"]["lost_on_receive"].get<long long>(), 10) << channel;
    EXPECT_EQ(j["log"]["missing_ticks"][channel], 0)
        << channel << j["log"].dump();  // ... and nothing is missing
  }
  EXPECT_GT(j["processes"]["controller"]["channels"]["PLANT_POSITION"]["injected"]["lost_on_receive"]
                .get<long long>(),
            10);
  EXPECT_EQ(j["log"]["missing_samples"], 0);
  // Re-sent ticks are in the log a few ticks late; replay and report put them in tick order.
  expectTheFaultFreeRun(clean, lossy);
  const std::string report = freshDir("faults-receivers-report");
  ASSERT_EQ(lagrange("report " + quote(lossy + "/run.lcm") + " -o " + quote(report)).exit_code, 0);
  for (const std::string channel : {"PLANT_TRUTH", "CONTROL_COMMAND", "ACTUATOR_STATE"}) {
    std::ifstream csv(report + "/" + channel + ".csv");
    std::string line;
    std::getline(csv, line);  // header: tick first
    long long rows = 0, in_order = 0;
    for (long long previous = -1; std::getline(csv, line); ++rows) {
      const long long tick = std::stoll(line.substr(0, line.find(',')));
      in_order += tick == previous + 1;
      previous = tick;
    }
    EXPECT_EQ(rows, 1001) << channel;
    EXPECT_EQ(in_order, 1001) << channel << ": rows out of tick order";
  }
}

TEST(Faults, RealtimeUnderDropsAndDelaysConvergesAndTheCountersAddUp) {
  const std::string faulty = freshDir("faults-realtime");
  const RunResult r = runScenario(kRigid, faulty,
                                  "-q --mode realtime --set duration=4 --set realtime.hold_periods=200 "
                                  "--set 'faults.channels.all={drop: 0.01, delay_jitter: 0.002}'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(faulty);
  // The scenario's own metric, not a ratio to a fault-free run's convergence
  // time: in realtime that time also depends on the machine's load (0.9 s
  // fault-free; 2.8 s under these faults in one run while a build ran beside).
  // hold_periods = 200: a loaded machine's stall of 20+ ms (seen: 35 periods)
  // then holds the torque instead of dropping the arm just before the end.
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  EXPECT_LT(j["tracking"]["final_error"].get<double>(), j["tracking"]["tolerance"].get<double>());
  // The delays made torques late (the faults happened) and the plant applied
  // them under "hold" (zeroed: only the first ticks, before any torque came).
  const auto& stale = j["messages"]["stale"]["plant"];
  std::printf("plant: %lld torques held, %lld zeroed\n", stale["torque_held"].get<long long>(),
              stale["torque_zeroed"].get<long long>());
  EXPECT_GT(stale["torque_held"].get<long long>(), 0) << stale.dump();
  EXPECT_LT(stale["torque_zeroed"].get<long long>(), 20) << stale.dump();

  const auto& position = j["messages"]["PLANT_POSITION"];
  const long long published = position["published"], dropped = position["injected"]["dropped"],
                  delayed = position["injected"]["delayed"];
  std::printf("PLANT_POSITION: published %lld, dropped %lld, delayed %lld\n", published, dropped, delayed);
  EXPECT_GT(dropped, 0);
  EXPECT_NEAR(static_cast<double>(dropped) / static_cast<double>(published), 0.01, 0.007);
  EXPECT_GT(delayed, published / 2);
  // Every position the plant sent and did not drop reached the controller,
  // accepted, or rejected as overtaken by a later one (old_or_repeated).
  const auto& at_controller = j["processes"]["controller"]["channels"]["PLANT_POSITION"];
  const long long arrived =
      at_controller["received"].get<long long>() + at_controller["rejected"].get<long long>();
  EXPECT_LE(std::llabs(arrived - (published - dropped)), 3) << at_controller.dump();
  EXPECT_EQ(at_controller["rejected"], at_controller["rejected_by_reason"]["old_or_repeated"]);
  // Realtime does not re-send: the log misses exactly the samples dropped on the way to it.
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["log"]["missing_samples"], j["messages"]["PLANT_TRUTH"]["injected"]["dropped"]);
  EXPECT_EQ(j["log"]["missing_ticks"]["PLANT_TRUTH"], j["messages"]["PLANT_TRUTH"]["injected"]["dropped"]);
  EXPECT_EQ(j["log"]["missing_ticks"]["PLANT_POSITION"], dropped) << j["log"].dump();
}

}  // namespace
}  // namespace lagrange::testing
