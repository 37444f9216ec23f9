// The logger's rules without LCM or a clock: which tick its STATUS confirms
// (logger/tick_confirmation.hpp) and when it stops recording
// (logger/run_end.hpp).

#include <gtest/gtest.h>

#include "logger/run_end.hpp"
#include "logger/tick_confirmation.hpp"

namespace lagrange::logger {
namespace {

using std::chrono::milliseconds;
const std::vector<std::string> kTwoChannels = {"A", "B"};

TEST(TickConfirmation, LockstepConfirmsOnlyTicksEveryChannelHasUpToThem) {
  TickConfirmation c(kTwoChannels, 10, /*lockstep=*/true, 8);
  c.record("A", 0, 0);
  c.record("A", 1, 1);
  EXPECT_EQ(c.confirmed(1), -1) << "B has no tick yet";
  c.record("B", 1, 1);
  EXPECT_EQ(c.confirmed(1), -1) << "B lacks tick 0: the plant must re-send it";
  c.record("B", 0, 1);
  EXPECT_EQ(c.confirmed(1), 1);
  EXPECT_EQ(c.confirmed(0), 0) << "never past the newest tracking sample";
}

TEST(TickConfirmation, RealtimeConfirmsTheNewestSampleWhateverIsMissing) {
  TickConfirmation c(kTwoChannels, 10, /*lockstep=*/false, 8);
  c.record("A", 3, 3);
  EXPECT_EQ(c.confirmed(3), 3);
}

TEST(TickConfirmation, AStatusIsDueEveryQuarterWindow) {
  TickConfirmation c({"A"}, 100, true, 8);  // every 2 ticks
  EXPECT_EQ(c.acknowledge(-1), -1);
  c.record("A", 0, 0);
  EXPECT_FALSE(c.acknowledgementDue());
  c.record("A", 1, 1);
  EXPECT_TRUE(c.acknowledgementDue());
  EXPECT_EQ(c.acknowledge(1), 1);
  EXPECT_FALSE(c.acknowledgementDue()) << "the STATUS went out";
  c.record("A", 2, 2);
  EXPECT_FALSE(c.acknowledgementDue());
  c.record("A", 3, 3);
  EXPECT_TRUE(c.acknowledgementDue());
}

TEST(TickConfirmation, MissingTicksPerChannelAndForeignOnesIgnored) {
  TickConfirmation c(kTwoChannels, 5, true, 8);
  for (int64_t k : {0, 1, 3}) c.record("A", k, k);
  c.record("B", 2, 3);
  c.record("C", 0, 3);     // not a channel of the run
  c.record("A", 1000, 3);  // beyond the run: ignored, nothing allocated for it
  const auto missing = c.missingUpTo(3);
  EXPECT_EQ(missing.size(), 2u);
  EXPECT_EQ(missing.at("A"), 1);
  EXPECT_EQ(missing.at("B"), 3);
}

const RunEnd::Clock::time_point t0{};

using State = RunEnd::State;

TEST(RunEnd, EndsWhenEveryProcessFinished) {
  RunEnd end(milliseconds(2000), t0);
  end.processState("plant", State::kFinished, t0);
  EXPECT_FALSE(end.due(t0, false)) << "controller and actuator have not finished yet";
  end.processState("controller", State::kFinished, t0);
  end.processState("actuator", State::kRunning, t0);
  EXPECT_FALSE(end.due(t0 + milliseconds(10), false));
  end.processState("actuator", State::kFinished, t0);
  EXPECT_TRUE(end.due(t0 + milliseconds(10), false));
}

TEST(RunEnd, EndsAGraceAfterThePlantWhenOthersAreSilent) {
  RunEnd end(milliseconds(2000), t0);
  end.processState("plant", State::kFinished, t0);
  EXPECT_FALSE(end.due(t0 + milliseconds(2000), false));
  EXPECT_TRUE(end.due(t0 + milliseconds(2001), false));
}

TEST(RunEnd, EndsAGraceAfterEveryTickWhenThePlantsStatusIsLost) {
  RunEnd end(milliseconds(2000), t0);
  EXPECT_FALSE(end.due(t0, false));
  EXPECT_FALSE(end.due(t0 + milliseconds(500), true)) << "the grace starts when every tick is confirmed";
  EXPECT_FALSE(end.due(t0 + milliseconds(2500), true));
  EXPECT_TRUE(end.due(t0 + milliseconds(2501), true));
}

// A run spread over hosts whose plant's host died: the logger must not wait forever.
TEST(RunEnd, APlantSilentPastTheLimitIsGoneUnlessItFinished) {
  RunEnd end(milliseconds(2000), t0);
  const auto limit = milliseconds(4000), start = milliseconds(6000);
  EXPECT_FALSE(end.plantGone(t0 + milliseconds(6000), limit, start)) << "never heard: the start allowance";
  EXPECT_EQ(end.plantGone(t0 + milliseconds(6001), limit, start), milliseconds(6001));
  end.plantHeard(t0 + milliseconds(3000));
  EXPECT_FALSE(end.plantGone(t0 + milliseconds(7000), limit, start));
  EXPECT_TRUE(end.plantGone(t0 + milliseconds(7001), limit, start)) << "once heard: the shorter limit";
  end.plantHeard(t0 + milliseconds(1000));  // a late message does not move it back
  EXPECT_TRUE(end.plantGone(t0 + milliseconds(7001), limit, start));
  end.processState("plant", State::kFinished, t0 + milliseconds(7500));
  EXPECT_FALSE(end.plantGone(t0 + milliseconds(60000), limit, start)) << "finished is not gone";
}

TEST(RunEnd, AllEndedMeansEveryoneFinishedOrWasInterrupted) {
  RunEnd end(milliseconds(2000), t0);
  end.processState("plant", State::kInterrupted, t0);
  end.processState("controller", State::kFinished, t0);
  EXPECT_FALSE(end.allEnded());
  end.processState("actuator", State::kReady, t0);
  EXPECT_FALSE(end.allEnded()) << "ready is not an end";
  end.processState("actuator", State::kInterrupted, t0);
  EXPECT_TRUE(end.allEnded());
  EXPECT_FALSE(end.allReported(State::kFinished));
}

}  // namespace
}  // namespace lagrange::logger
