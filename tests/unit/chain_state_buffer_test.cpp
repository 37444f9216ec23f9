// The controller's chain states by tick: a stray far-future state neither
// replaces the one a lockstep run waits for nor grows the buffer without bound.
#include "controller/chain_state_buffer.hpp"

#include <gtest/gtest.h>

namespace lagrange::controller {
namespace {

Eigen::MatrixXd state(double v) { return Eigen::MatrixXd::Constant(1, 2, v); }

TEST(ChainStateBuffer, AnswersEachTickWithItsOwnStateDespiteAFarFutureOne) {
  ChainStateBuffer buffer(state(0.0));
  buffer.put(1000000001, state(99.0));  // e.g. another run's ACTUATOR_STATE of tick 1e9
  ASSERT_TRUE(buffer.take(0).has_value());
  EXPECT_EQ(*buffer.take(0), state(0.0));    // the initial state, asked twice (a re-sent position)
  EXPECT_FALSE(buffer.take(1).has_value());  // not heard yet: stay silent
  buffer.put(1, state(1.0));
  EXPECT_EQ(*buffer.take(1), state(1.0));
  buffer.put(0, state(-1.0));  // older than what was asked for: ignored
  EXPECT_FALSE(buffer.take(0).has_value());
  EXPECT_EQ(buffer.size(), 2u);  // tick 1 and the stray one
}

TEST(ChainStateBuffer, StaysBoundedUnderAFloodOfFutureTicks) {
  ChainStateBuffer buffer(state(0.0));
  for (int64_t k = 1000; k < 5000; ++k) buffer.put(k, state(static_cast<double>(k)));
  EXPECT_EQ(buffer.size(), ChainStateBuffer::kCapacity);
  buffer.put(1, state(1.0));  // the one the run needs still gets in (the farthest future goes)
  EXPECT_EQ(*buffer.take(1), state(1.0));
  EXPECT_EQ(buffer.size(), ChainStateBuffer::kCapacity - 1);  // asking for tick 1 forgot tick 0
}

}  // namespace
}  // namespace lagrange::controller
