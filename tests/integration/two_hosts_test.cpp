// A run spread over two hosts (tests/integration/two_hosts.sh: network
// namespaces joined by a veth pair, multicast routed, LCM TTL 1): plant and
// actuator on one, controller and logger on the other. The scenario
// converges, the log on the logger's host is complete, and -- lockstep being
// deterministic -- the trajectory is bit for bit that of a one-host run.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>

#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

const std::string kSource = LAGRANGE_SOURCE_DIR;

TEST(TwoHosts, PlantAndActuatorOnOneControllerAndLoggerOnTheOther) {
  const std::string out = freshDir("two-hosts");
  const std::string config = kSource + "/configs/rigid_2dof.yaml";
  const RunResult r = shell("bash " + quote(kSource + "/tests/integration/two_hosts.sh") + " " + quote(kBin) +
                            " " + quote(config) + " " + quote(out) + " -q --set duration=2");
  ASSERT_NE(r.output.find("exit codes: 0 0"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/a/run.lcm")) << "the logger ran on host A";

  const auto j = readSummary(out + "/b");
  EXPECT_EQ(j["status"], "completed");
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  EXPECT_EQ(j["tracking"]["samples"], 2001);

  // Complete: every tick of every channel crossed the link into the log.
  std::map<std::string, std::set<long long>> ticks;
  for (const auto& [channel, tick] : readTicks(out + "/b/run.lcm")) ticks[channel].insert(tick);
  for (const char* channel : {"PLANT_POSITION", "PLANT_TRUTH", "CONTROL_COMMAND", "ACTUATOR_STATE"})
    EXPECT_EQ(ticks[channel].size(), 2001u) << channel;

  const std::string here = freshDir("one-host");
  ASSERT_EQ(runScenario(config, here, "-q --set duration=2").exit_code, 0);
  const auto spread = readTruth(out + "/b/run.lcm"), local = readTruth(here + "/run.lcm");
  ASSERT_EQ(spread.size(), local.size());
  const size_t common = forCommonTicks(spread, local, [](const TruthSample& a, const TruthSample& b) {
    EXPECT_TRUE(a.q == b.q && a.qdot == b.qdot) << "tick " << a.tick << " differs from the one-host run";
  });
  EXPECT_EQ(common, 2001u);
}

}  // namespace
}  // namespace lagrange::testing
