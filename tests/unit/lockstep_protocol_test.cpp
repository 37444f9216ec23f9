// The plant's lockstep rules (plant/lockstep_protocol.hpp) without LCM or a
// clock: the window ahead of the logger, the answer to the awaited tick, and
// the re-sends, driven by hand-made times.

#include "plant/lockstep_protocol.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lagrange::plant {
namespace {

using Protocol = LockstepProtocol<std::string>;
using Clock = Protocol::Clock;
using std::chrono::milliseconds;

const Clock::time_point t0{};

Protocol protocol(int64_t last_tick = 10, int window = 2) {
  return Protocol({last_tick, window, milliseconds(20)});
}

std::vector<std::string> values(const std::vector<const std::string*>& sent) {
  std::vector<std::string> out;
  for (const std::string* s : sent) out.push_back(*s);
  return out;
}

TEST(LockstepProtocol, NothingGoesOutBeforeTheLoggerIsHeard) {
  Protocol p = protocol();
  EXPECT_FALSE(p.loggerHeard());
  EXPECT_FALSE(p.mayPublish(0));
  p.loggerConfirmed(-1);  // the logger's "ready": nothing recorded yet
  EXPECT_TRUE(p.loggerHeard());
  EXPECT_TRUE(p.mayPublish(0));
  EXPECT_EQ(p.loggerTick(), -1);
}

TEST(LockstepProtocol, ThePlantStaysWithinTheWindowOfTheLogger) {
  Protocol p = protocol(10, 2);
  p.loggerConfirmed(3);
  EXPECT_TRUE(p.mayPublish(5));
  EXPECT_FALSE(p.mayPublish(6));
  p.loggerConfirmed(1);  // an older STATUS overtaken on the way changes nothing
  EXPECT_EQ(p.loggerTick(), 3);
  EXPECT_FALSE(p.mayPublish(6));
  p.loggerConfirmed(4);
  EXPECT_TRUE(p.mayPublish(6));
}

TEST(LockstepProtocol, OnlyTheFirstStateOfTheAwaitedTickAnswersIt) {
  Protocol p = protocol();
  p.loggerConfirmed(-1);
  p.published(0, "tick 0", t0);
  EXPECT_FALSE(p.answered());
  p.published(1, "tick 1", t0);
  EXPECT_FALSE(p.actuatorState(0)) << "a stale answer (the previous tick) is ignored";
  EXPECT_FALSE(p.answered());
  EXPECT_TRUE(p.actuatorState(1));
  EXPECT_TRUE(p.answered());
  EXPECT_FALSE(p.actuatorState(1)) << "a repeated answer is ignored: its torque was taken";
  EXPECT_FALSE(p.actuatorState(2)) << "an answer to a tick not yet sent is ignored";
}

TEST(LockstepProtocol, AnUnansweredTickIsResentEveryTimeout) {
  Protocol p = protocol();
  p.loggerConfirmed(-1);
  p.published(0, "tick 0", t0);
  EXPECT_FALSE(p.positionResendDue(t0 + milliseconds(19)));
  EXPECT_TRUE(p.positionResendDue(t0 + milliseconds(20)));
  EXPECT_FALSE(p.positionResendDue(t0 + milliseconds(39))) << "the timer restarts at the re-send";
  EXPECT_TRUE(p.positionResendDue(t0 + milliseconds(40)));
  EXPECT_EQ(p.retransmits(), 2);
  p.actuatorState(0);
  EXPECT_FALSE(p.positionResendDue(t0 + milliseconds(100))) << "an answered tick is not re-sent";
  EXPECT_EQ(p.retransmits(), 2);
}

TEST(LockstepProtocol, TheLoggerGetsEveryUnconfirmedTickAgainAfterTheTimeout) {
  Protocol p = protocol(10, 2);
  p.loggerConfirmed(-1);
  for (int64_t k = 0; k <= 2; ++k) {
    p.published(k, "tick " + std::to_string(k), t0);
    p.actuatorState(k);
  }
  EXPECT_FALSE(p.mayPublish(3));
  p.awaitLogger(t0);
  EXPECT_TRUE(p.logResendsDue(t0 + milliseconds(19)).empty());
  p.loggerConfirmed(0);  // tick 0 is in the log; ticks 1 and 2 are not (yet)
  EXPECT_EQ(values(p.logResendsDue(t0 + milliseconds(20))), (std::vector<std::string>{"tick 1", "tick 2"}));
  EXPECT_EQ(p.logResends(), 2);
  EXPECT_TRUE(p.logResendsDue(t0 + milliseconds(21)).empty()) << "the timer restarts at the re-send";
  p.loggerConfirmed(2);
  EXPECT_TRUE(p.logResendsDue(t0 + milliseconds(40)).empty()) << "confirmed ticks are forgotten";
  EXPECT_EQ(p.unconfirmedTicks(), 0u);
  EXPECT_TRUE(p.mayPublish(3));
}

TEST(LockstepProtocol, NoLogResendsWhileTheLoggerIsUnheard) {
  Protocol p = protocol();
  p.awaitLogger(t0);
  EXPECT_TRUE(p.logResendsDue(t0 + milliseconds(100)).empty());
  EXPECT_EQ(p.logResends(), 0);
}

TEST(LockstepProtocol, TheKeptTicksAreBoundedByTheWindow) {
  Protocol p = protocol(1000, 3);
  p.loggerConfirmed(-1);
  for (int64_t k = 0; k <= 100; ++k) {
    ASSERT_TRUE(p.mayPublish(k));
    p.published(k, "x", t0);
    p.actuatorState(k);
    p.loggerConfirmed(k - 2);  // the logger two ticks behind
    EXPECT_LE(p.unconfirmedTicks(), 4u);
  }
}

TEST(LockstepProtocol, TheRunEndsWhenTheLoggerConfirmedTheLastTick) {
  Protocol p = protocol(3, 10);
  EXPECT_FALSE(p.allConfirmed());
  p.loggerConfirmed(2);
  EXPECT_FALSE(p.allConfirmed());
  p.loggerConfirmed(3);
  EXPECT_TRUE(p.allConfirmed());
}

}  // namespace
}  // namespace lagrange::plant
