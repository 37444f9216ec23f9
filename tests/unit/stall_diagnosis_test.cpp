// What a stalled lockstep run says (plant/stall_diagnosis.hpp): it follows the
// ring back from the plant and names whom it waited for, on which channel,
// and what was seen instead -- from the processes' STATUS counters.
#include "plant/stall_diagnosis.hpp"

#include <gtest/gtest.h>

namespace lagrange::plant {
namespace {

lagrange::channel_stats_t channel(const std::string& name, int64_t received) {
  lagrange::channel_stats_t c{};
  c.channel = name;
  c.received = received;
  return c;
}

lagrange::status_t status(const std::string& process, const std::string& state, int64_t last_tick,
                          std::vector<lagrange::channel_stats_t> channels = {}) {
  lagrange::status_t s{};
  s.process = process;
  s.state = state;
  s.last_tick = last_tick;
  s.channels = std::move(channels);
  s.num_channels = static_cast<int32_t>(s.channels.size());
  return s;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(StallDiagnosis, RejectionsAreSpelledOutByReason) {
  lagrange::channel_stats_t c = channel("CONTROL_COMMAND", 3);
  EXPECT_EQ(describeRejections(c), "");
  c.rejected = 214;
  c.rejected_unauthenticated = 200;
  c.rejected_corrupt = 14;
  EXPECT_EQ(describeRejections(c), "214 (200 unauthenticated, 14 corrupt (checksum))");
}

// The case: an external controller whose commands all fail the
// check. The actuator heard them and says so; the controller is named.
TEST(StallDiagnosis, ACommandTheActuatorRejectsNamesTheControllerAndWhy) {
  lagrange::channel_stats_t commands = channel("CONTROL_COMMAND", 0);
  commands.rejected = 214;
  commands.rejected_corrupt = 214;
  StallFacts f{0, 10.0, {}, {}};
  f.peers["actuator"] = status("actuator", "ready", -1, {commands});
  f.peers["controller"] = status("controller", "ready", -1);
  const std::string why = describeAnswerStall(f);
  EXPECT_TRUE(has(why, "stalled at tick 0")) << why;
  EXPECT_TRUE(has(why, "in 10 s")) << why;
  EXPECT_TRUE(has(why, "awaited: the controller -- no valid CONTROL_COMMAND for tick 0 reached the actuator"))
      << why;
  EXPECT_TRUE(has(why, "rejected 214 (214 corrupt (checksum))")) << why;
  EXPECT_TRUE(has(why, "reports no counters of PLANT_POSITION"))
      << why;  // an external program's empty STATUS
}

// A command refused as invalid (a NaN from a program without the SDK): the
// actuator's STATUS names the last one and who sent it, and so does the stall.
TEST(StallDiagnosis, ACommandRefusedAsInvalidIsQuotedWithItsSender) {
  lagrange::channel_stats_t commands = channel("CONTROL_COMMAND", 0);
  commands.rejected = commands.rejected_invalid = 193;
  StallFacts f{0, 10.0, {}, {}};
  f.peers["actuator"] = status("actuator", "ready", -1, {commands});
  f.peers["actuator"].message =
      "last refused as invalid: CONTROL_COMMAND: u[0] is not finite (nan) (from 'controller', tick 0)";
  const std::string why = describeAnswerStall(f);
  EXPECT_TRUE(has(why,
                  "rejected 193 (193 invalid) -- last refused as invalid: CONTROL_COMMAND: u[0] is not "
                  "finite (nan) (from 'controller', tick 0)"))
      << why;
}

TEST(StallDiagnosis, ASilentControllerAndAForgerOnStatusAreBothNamed) {
  StallFacts f{7, 2.5, {}, {}};
  f.peers["actuator"] = status("actuator", "running", 6, {channel("CONTROL_COMMAND", 7)});
  lagrange::channel_stats_t own_status = channel("STATUS", 40);
  own_status.rejected = 5;
  own_status.rejected_unauthenticated = 5;
  f.own = {own_status};
  const std::string why = describeAnswerStall(f);
  EXPECT_TRUE(has(why, "stalled at tick 7")) << why;
  EXPECT_TRUE(has(why, "the controller was never heard")) << why;
  EXPECT_TRUE(has(why, "accepted 7 CONTROL_COMMAND and rejected none")) << why;
  EXPECT_TRUE(has(why, "the plant itself rejected 5 (5 unauthenticated) STATUS")) << why;
}

TEST(StallDiagnosis, AnAnswerLostOnTheWayIsNotBlamedOnTheController) {
  StallFacts f{3, 10.0, {}, {}};
  f.peers["actuator"] = status("actuator", "running", 3);
  const std::string why = describeAnswerStall(f);
  EXPECT_TRUE(has(why, "lost on the way")) << why;
  EXPECT_FALSE(has(why, "controller")) << why;
  EXPECT_TRUE(has(describeAnswerStall({3, 10.0, {}, {}}), "the actuator, never heard"));
}

TEST(StallDiagnosis, TheLoggerAndTheHandshakeNameWhoIsMissing) {
  StallFacts f{25, 10.0, {}, {}};
  EXPECT_TRUE(has(describeLoggerStall(f, -1), "the logger confirmed no tick"));
  EXPECT_TRUE(has(describeLoggerStall(f, -1), "the logger was never heard"));
  f.peers["logger"] = status("logger", "running", 4, {channel("PLANT_TRUTH", 5)});
  const std::string why = describeLoggerStall(f, 4);
  EXPECT_TRUE(has(why, "stalled before tick 25: the logger confirmed ticks up to 4")) << why;
  EXPECT_TRUE(has(why, "accepted 5 PLANT_TRUTH")) << why;
  const std::string missing = describeMissingPeers(f, {"logger", "controller", "actuator"});
  EXPECT_TRUE(has(missing, "no STATUS from controller, actuator in 10 s")) << missing;
}

}  // namespace
}  // namespace lagrange::plant
