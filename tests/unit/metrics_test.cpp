// Tracking metrics.
#include <gtest/gtest.h>

#include "logger/tick_coverage.hpp"
#include "logger/tracking_metrics.hpp"

namespace lagrange {
namespace {

model::Reference zeroReference() {
  model::ReferenceParams p;
  p.type = model::ReferenceType::kSine;
  p.offset = p.amplitude = p.frequency = p.phase = Eigen::VectorXd::Zero(1);
  return model::Reference(p);
}

TEST(TrackingMetrics, ConvergenceTimeIsTheSampleAfterTheLastViolation) {
  logger::TrackingMetrics m(zeroReference(), 0.1);
  const double errors[] = {1.0, 0.05, 0.2, 0.09, 0.01, 0.02};
  for (int k = 0; k < 6; ++k) m.addSample(k, 0.5 * k, Eigen::VectorXd::Constant(1, errors[k]));
  EXPECT_FALSE(m.addSample(3, 9.0, Eigen::VectorXd::Constant(1, 5.0)));  // repeated tick ignored
  const auto s = m.summary();
  ASSERT_TRUE(s.convergence_time.has_value());
  EXPECT_DOUBLE_EQ(*s.convergence_time, 1.5);
  EXPECT_DOUBLE_EQ(s.max_error, 1.0);
  EXPECT_DOUBLE_EQ(s.final_error, 0.02);
  // Last second: samples at t = 1.5, 2.0, 2.5.
  EXPECT_NEAR(s.rms_last_second, std::sqrt((0.09 * 0.09 + 0.01 * 0.01 + 0.02 * 0.02) / 3), 1e-15);
}

// Two joints, two torque steps per 0.01 s period, the ticks out of order and
// one repeated: each counts once, in tick order.
TEST(TrackingMetrics, TorqueMaxTotalVariationAndEnergyCountEachTickOnceInOrder) {
  logger::TrackingMetrics m(zeroReference(), 0.1, 1e-2, 0.01);
  m.addSample(0, 0.0, Eigen::VectorXd::Zero(1));
  Eigen::MatrixXd tick0(2, 2), tick1(2, 2);
  tick0 << 1.0, -2.0, 3.0, -2.0;
  tick1 << 3.0, 0.0, -1.0, 0.0;
  m.addTorque(1, tick1);
  m.addTorque(0, tick0);
  m.addTorque(1, Eigen::MatrixXd::Constant(2, 2, 100.0));  // a repeated tick: ignored
  const auto s = m.summary();
  EXPECT_DOUBLE_EQ(s.max_abs_torque, 3.0);
  // Steps in order: (1,-2) (3,-2) (3,0) (-1,0): |2|+|0| + |0|+|2| + |4|+|0| = 8.
  EXPECT_DOUBLE_EQ(s.torque_total_variation, 8.0);
  // Each step held 0.005 s: (5 + 13 + 9 + 1) * 0.005.
  EXPECT_DOUBLE_EQ(s.control_energy, 28.0 * 0.005);
}

TEST(TrackingMetrics, NeverConvergedIsEmpty) {
  logger::TrackingMetrics m(zeroReference(), 0.1);
  m.addSample(0, 0.0, Eigen::VectorXd::Constant(1, 0.01));
  m.addSample(1, 1.0, Eigen::VectorXd::Constant(1, 0.5));
  EXPECT_FALSE(m.summary().convergence_time.has_value());
}

TEST(TrackingMetrics, ChainErrorsAreJudgedPerStage) {
  logger::TrackingMetrics m(zeroReference(), 0.1, 0.5);
  m.addSample(0, 0.0, Eigen::VectorXd::Constant(1, 0.0));
  m.addChainErrors(0, 0.0, {{3.0}, {4.0}});
  m.addChainErrors(1, 1.0, {{0.1}, {0.6}});
  m.addChainErrors(1, 1.0, {{9.0}, {9.0}});  // repeated tick ignored
  m.addChainErrors(2, 2.0, {{0.2}, {0.3}});
  const auto s = m.summary();
  ASSERT_EQ(s.chain.size(), 2u);
  EXPECT_DOUBLE_EQ(*s.chain[0].convergence_time, 1.0);
  EXPECT_DOUBLE_EQ(*s.chain[1].convergence_time, 2.0);
  EXPECT_DOUBLE_EQ(s.chain[1].max_error, 4.0);
  EXPECT_DOUBLE_EQ(s.chain[0].final_error, 0.2);
}

}  // namespace
}  // namespace lagrange

namespace lagrange::logger {
namespace {

// The log's per-channel tick coverage: gaps counted up to the newest sample,
// repeats counted once, ticks outside the run ignored (not allocated).
TEST(TickCoverage, CountsTheTicksWithNoMessage) {
  TickCoverage c(9);  // a run of ticks 0..9
  EXPECT_EQ(c.missingUpTo(9), 10);
  for (int64_t k : {0, 1, 1, 3, 4, 9}) c.add(k);
  EXPECT_EQ(c.missingUpTo(4), 1);  // tick 2
  EXPECT_EQ(c.missingUpTo(9), 5);  // 2, 5, 6, 7, 8
  c.add(-1);
  c.add(int64_t{1} << 60);  // forged or corrupt: beyond the run
  EXPECT_EQ(c.missingUpTo(int64_t{1} << 61), 5);
  EXPECT_EQ(c.missingUpTo(-1), 0);
}

}  // namespace
}  // namespace lagrange::logger

namespace lagrange::logger {
namespace {

// What the logger confirms to the plant: every tick up to it present.
TEST(TickCoverage, ContiguousThroughStopsAtTheFirstGap) {
  TickCoverage c(5);
  EXPECT_EQ(c.contiguousThrough(), -1);
  c.add(1);
  EXPECT_EQ(c.contiguousThrough(), -1);  // tick 0 missing
  c.add(0);
  EXPECT_EQ(c.contiguousThrough(), 1);
  c.add(3);
  c.add(5);
  EXPECT_EQ(c.contiguousThrough(), 1);  // tick 2 missing
  c.add(2);
  EXPECT_EQ(c.contiguousThrough(), 3);
  c.add(4);
  EXPECT_EQ(c.contiguousThrough(), 5);
}

}  // namespace
}  // namespace lagrange::logger
