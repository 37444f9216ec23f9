// Tracking metrics and the pass-through actuator.
#include <gtest/gtest.h>

#include "actuator/passthrough.hpp"
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

TEST(TrackingMetrics, NeverConvergedIsEmpty) {
  logger::TrackingMetrics m(zeroReference(), 0.1);
  m.addSample(0, 0.0, Eigen::VectorXd::Constant(1, 0.01));
  m.addSample(1, 1.0, Eigen::VectorXd::Constant(1, 0.5));
  EXPECT_FALSE(m.summary().convergence_time.has_value());
}

TEST(PassthroughActuator, PassesOrSaturatesPerJoint) {
  const actuator::PassthroughActuator free(2, std::nullopt);
  EXPECT_EQ(free.step(Eigen::Vector2d(500, -3)).tau, Eigen::Vector2d(500, -3));
  const actuator::PassthroughActuator limited(2, Eigen::Vector2d(10, 1));
  const auto out = limited.step(Eigen::Vector2d(500, -3));
  EXPECT_EQ(out.tau, Eigen::Vector2d(10, -1));
  EXPECT_TRUE(out.saturated(0) && out.saturated(1));
  EXPECT_FALSE(limited.step(Eigen::Vector2d(5, 0.5)).saturated.any());
  EXPECT_THROW(actuator::PassthroughActuator(2, Eigen::Vector2d(1, 0)), std::invalid_argument);
  EXPECT_THROW(limited.step(Eigen::Vector3d::Zero()), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange
