// The reactive processes' rules (runtime/tick_responder.hpp,
// runtime/realtime_responder.hpp) driven through a fake node: no LCM, the
// traffic delivered by hand or one step per poll.

#include <gtest/gtest.h>

#include "runtime/realtime_responder.hpp"
#include "runtime/tick_responder.hpp"
#include "support/fake_node.hpp"
#include "transport/channels.hpp"

namespace lagrange::runtime {
namespace {

using lagrange::testing::FakeNode;
using Position = lagrange::plant_position_t;
constexpr const char* kIn = transport::kPlantPosition;
constexpr const char* kOut = "ANSWER";
constexpr int kJoints = 2;

Position position(int64_t tick, double q0 = 0.0, int joints = kJoints) {
  Position m{};
  m.header = transport::makeHeader(tick, 0.001 * static_cast<double>(tick));
  m.num_joints = joints;
  m.q.assign(static_cast<size_t>(joints), q0);
  return m;
}

lagrange::status_t status(const std::string& process, const std::string& state) {
  lagrange::status_t s{};
  s.header = transport::makeHeader(0, 0.0);
  s.process = process;
  s.state = state;
  return s;
}

// The answer records which input it came from and how many computations preceded it.
struct Answerer {
  int calls = 0;
  std::optional<Position> operator()(const Position& in) {
    ++calls;
    return position(in.header.tick, 100.0 * calls);
  }
};

std::vector<int64_t> ticks(const std::vector<Position>& sent) {
  std::vector<int64_t> out;
  for (const Position& m : sent) out.push_back(m.header.tick);
  return out;
}

// A responder keeping the answers of the last `history` ticks, on a fake node.
class TickResponder : public ::testing::Test {
 protected:
  std::shared_ptr<const std::optional<Position>> start(int history) {
    return respondPerTick<Position, Position>(node, kIn, kOut, kJoints, progress, history, std::ref(compute));
  }
  FakeNode node{"controller"};
  Progress progress;
  Answerer compute;
};

TEST_F(TickResponder, AnswersEachTickOnceAndARepeatFromWhatItSent) {
  const auto newest = start(8);
  for (int64_t k : {0, 1, 1, 2}) node.deliver(kIn, position(k));
  const auto sent = node.published<Position>(kOut);
  EXPECT_EQ(ticks(sent), (std::vector<int64_t>{0, 1, 1, 2}));
  EXPECT_EQ(compute.calls, 3) << "a repeated tick never steps the core twice";
  EXPECT_EQ(sent[2].q, sent[1].q) << "the repeat is the answer already sent";
  EXPECT_EQ(progress.last_tick, 2);
  ASSERT_TRUE(newest->has_value());
  EXPECT_EQ((*newest)->header.tick, 2);
}

TEST_F(TickResponder, ADeclinedTickIsAnsweredWhenItComesAgain) {
  bool ready = false;
  respondPerTick<Position, Position>(node, kIn, kOut, kJoints, progress, 8,
                                     [&](const Position& in) -> std::optional<Position> {
                                       if (!ready) return std::nullopt;
                                       return position(in.header.tick);
                                     });
  node.deliver(kIn, position(0));
  EXPECT_TRUE(node.published<Position>(kOut).empty()) << "another input of the tick is missing: stay silent";
  EXPECT_EQ(progress.last_tick, -1);
  ready = true;
  node.deliver(kIn, position(0));  // the plant re-sends
  EXPECT_EQ(ticks(node.published<Position>(kOut)), (std::vector<int64_t>{0}));
  EXPECT_EQ(progress.last_tick, 0);
}

TEST_F(TickResponder, TicksOlderThanItsHistoryAreIgnored) {
  start(2);
  for (int64_t k = 0; k <= 4; ++k) node.deliver(kIn, position(k));
  node.deliver(kIn, position(1));  // past the history of 2: not answered, not computed again
  node.deliver(kIn, position(3));  // within it: answered again
  EXPECT_EQ(ticks(node.published<Position>(kOut)), (std::vector<int64_t>{0, 1, 2, 3, 4, 3}));
  EXPECT_EQ(compute.calls, 5);
}

TEST_F(TickResponder, AnInvalidInputNeverReachesTheCore) {
  start(8);
  node.deliver(kIn, position(0, 0.0, kJoints + 1));
  node.deliver(kIn, position(1, std::nan("")));
  EXPECT_EQ(node.rejected(), 2);
  EXPECT_EQ(compute.calls, 0);
  EXPECT_TRUE(node.published<Position>(kOut).empty());
}

TEST(ServeUntilPlantFinished, ReportsReadyThenFinishedWhenThePlantHasFinished) {
  FakeNode node("actuator");
  Progress progress;
  int idle_calls = 0;
  node.onPoll([&] {
    if (node.polls() == 2)
      node.deliver(transport::kStatus, status("controller", "finished"));  // not the plant
    if (node.polls() == 4) node.deliver(transport::kStatus, status("plant", "finished"));
  });
  EXPECT_EQ(serveUntilPlantFinished(
                node, progress, [&] { ++idle_calls; }, 0.0),
            0);
  EXPECT_EQ(node.polls(), 4) << "only the plant's 'finished' ends a reactive process";
  EXPECT_EQ(idle_calls, 4) << "with an idle time of 0 every poll without progress is idle";
  const auto reports = node.published<lagrange::status_t>(transport::kStatus);
  ASSERT_GE(reports.size(), 2u);
  EXPECT_EQ(reports.front().state, "ready");
  EXPECT_EQ(reports.back().state, "finished");
  EXPECT_EQ(reports.back().process, "actuator");
}

TEST(RealtimeResponder, ActsOnceOnEachFreshInputAndCountsTheRest) {
  FakeNode node("controller");
  const int64_t a_minute_ago = transport::nowUtime() - 60'000'000;
  node.onPoll([&] {
    auto fresh = [](int64_t tick) {
      Position m = position(tick);
      m.header.publish_utime = transport::nowUtime();
      return m;
    };
    switch (node.polls()) {
      case 1:
        node.deliver(kIn, fresh(0));
        break;
      case 2:
        break;  // nothing new: missing
      case 3: {
        Position old = position(1);
        old.header.publish_utime = a_minute_ago;
        node.deliver(kIn, old);  // stale: never acted on
        break;
      }
      case 4:
        node.deliver(kIn, fresh(2));
        break;
      case 5:
        node.deliver(kIn, fresh(1));
        break;  // older than the newest: ignored, so missing
      default:
        node.deliver(transport::kStatus, status("plant", "finished"));
    }
  });
  int calls = 0;
  const std::function<std::optional<Position>(const Position&)> compute = [&](const Position& in) {
    ++calls;
    return std::optional(position(in.header.tick));
  };
  // max_input_age 10 s: fresh inputs stay fresh on any machine, however loaded.
  EXPECT_EQ(serveRealtime(node, kIn, kOut, kJoints, {1e-3, 0.0, 10.0}, compute), 0);
  EXPECT_EQ(ticks(node.published<Position>(kOut)), (std::vector<int64_t>{0, 2}));
  EXPECT_EQ(calls, 2);
  const auto reports = node.published<lagrange::status_t>(transport::kStatus);
  ASSERT_FALSE(reports.empty());
  EXPECT_EQ(reports.front().state, "ready");
  const lagrange::status_t& last = reports.back();
  EXPECT_EQ(last.state, "finished");
  EXPECT_EQ(last.last_tick, 2);
  EXPECT_EQ(last.loop.stale_inputs, 1);
  EXPECT_EQ(last.loop.missing_inputs, 3) << "poll 2, poll 5 and the poll that brought the plant's end";
}

}  // namespace
}  // namespace lagrange::runtime
