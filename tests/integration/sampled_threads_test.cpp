// The sampled-data check's simulations run on threads in one process (#55):
// its verdict, times and errors must be the same bits on one thread and on
// four -- each loop its own ODE world with its own stepping dispatcher, the
// models and a free_motion reference's integration shared read-only. Before
// the worlds had dispatchers of their own, two worlds stepped at once shared
// ODE's one per process; before the URDF arm's solvers each had their own
// chain, a flexible URDF arm's loops corrupted each other (docs/sampled_data.md).
// In process, no LCM; short runs.
#include <gtest/gtest.h>

#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "config/scenario.hpp"
#include "support/configs.hpp"
#include "wiring/sampled_simulation.hpp"

namespace lagrange::testing {
namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool sameBits(const std::optional<double>& a, const std::optional<double>& b) {
  return a.has_value() == b.has_value() && (!a || sameBits(*a, *b));
}

void expectSame(const controller::SampledSimulation& one, const controller::SampledSimulation& four) {
  EXPECT_EQ(one.verdict, four.verdict);
  EXPECT_EQ(one.why, four.why);
  EXPECT_TRUE(sameBits(one.fine_rate, four.fine_rate));
  EXPECT_TRUE(sameBits(one.confirmed_at, four.confirmed_at));
  ASSERT_EQ(one.starts.size(), four.starts.size());
  for (size_t i = 0; i < one.starts.size(); ++i) {
    const controller::SampledSimulation::Start &a = one.starts[i], &b = four.starts[i];
    EXPECT_EQ(a.what, b.what);
    EXPECT_EQ(a.sampled_status, b.sampled_status) << a.what;
    EXPECT_EQ(a.fine_status, b.fine_status) << a.what;
    EXPECT_TRUE(sameBits(a.sampled_time, b.sampled_time)) << a.what;
    EXPECT_TRUE(sameBits(a.fine_time, b.fine_time)) << a.what;
    EXPECT_TRUE(sameBits(a.sampled_error, b.sampled_error)) << a.what;
    EXPECT_TRUE(sameBits(a.fine_error, b.fine_error)) << a.what;
    EXPECT_EQ(a.verdict, b.verdict) << a.what;
  }
}

class SampledOnThreads : public ::testing::TestWithParam<std::string> {};

TEST_P(SampledOnThreads, TheVerdictIsTheSameBitsOnOneThreadAndOnFour) {
  const config::Scenario s = config::loadScenario(kConfigs + "/" + GetParam() + ".yaml", {"duration=1.5"});
  const controller::SampledSimulation one = wiring::simulateSampledData(s, 1);
  const controller::SampledSimulation four = wiring::simulateSampledData(s, 4);
  ASSERT_EQ(one.starts.size(), 3u) << one.why;  // the initial state and two seeded ones
  expectSame(one, four);
}

// The Pelican (smooth_sine), the flexible Pelican (a free_motion reference
// shared by the loops) and the flexible URDF double pendulum (ODE and KDL).
INSTANTIATE_TEST_SUITE_P(Shipped, SampledOnThreads,
                         ::testing::Values("rigid_2dof", "flexible_2dof", "double_pendulum_flexible"));

// Two checks at once, each on two threads (lagrange tune calls the check
// from workers of its own): each gives what it gives alone.
TEST(SampledOnThreads, TwoChecksAtOnceGiveWhatEachGivesAlone) {
  const config::Scenario a = config::loadScenario(kRigid, {"duration=1.5"});
  const config::Scenario b = config::loadScenario(kConfigs + "/flexible_2dof.yaml", {"duration=1.5"});
  const controller::SampledSimulation alone_a = wiring::simulateSampledData(a, 1);
  const controller::SampledSimulation alone_b = wiring::simulateSampledData(b, 1);
  controller::SampledSimulation at_once_a;
  std::thread other([&] { at_once_a = wiring::simulateSampledData(a, 2); });
  const controller::SampledSimulation at_once_b = wiring::simulateSampledData(b, 2);
  other.join();
  expectSame(alone_a, at_once_a);
  expectSame(alone_b, at_once_b);
}

}  // namespace
}  // namespace lagrange::testing
