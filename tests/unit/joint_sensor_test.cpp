// The joint-angle sensor (plant/joint_sensor.hpp): ideal is the identity
// to the bit; the encoder reports the count below the angle; the delay line
// returns the angle of d ticks before; the noise has its sigma and the same
// seed gives the same draws.
#include "plant/joint_sensor.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace lagrange::plant {
namespace {

TEST(JointSensor, AnIdealSensorReturnsTheTrueAnglesBitForBit) {
  JointSensor sensor(2);
  EXPECT_TRUE(sensor.ideal());
  const Eigen::Vector2d q(0.1234567890123, -7.000000000001);
  EXPECT_EQ(sensor.measure(q), q);
}

TEST(JointSensor, AnEncoderReportsTheCountBelowTheAngle) {
  JointSensor sensor(2, {Eigen::Vector2d(4096, 0), Eigen::Vector2d::Zero(), 0, 1, {}});
  const double step = 2 * M_PI / 4096;
  for (const double angle : {0.3, -0.3, 7.1, -12.9, 3 * step}) {
    const Eigen::VectorXd m = sensor.measure(Eigen::Vector2d(angle, angle));
    EXPECT_LE(m(0), angle);
    EXPECT_GT(m(0), angle - step - 1e-15);
    EXPECT_NEAR(m(0) / step, std::round(m(0) / step), 1e-9) << "a whole number of counts";
    EXPECT_EQ(m(1), angle) << "joint 2 has no encoder";
  }
}

TEST(JointSensor, TheDelayLineReturnsTheAngleOfDTicksBefore) {
  JointSensor sensor(1, {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), 2, 1, {}});
  std::vector<double> read;
  for (int k = 0; k < 6; ++k) read.push_back(sensor.measure(Eigen::VectorXd::Constant(1, k))(0));
  EXPECT_EQ(read, (std::vector<double>{0, 0, 0, 1, 2, 3}));  // tick 0's angle held until tick d
}

TEST(JointSensor, NoiseHasItsSigmaAndTheSeedFixesTheDraws) {
  const double sigma = 1e-3;
  auto draws = [&](uint64_t seed) {
    JointSensor sensor(1, {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, sigma), 0, seed, {}});
    std::vector<double> out;
    for (int k = 0; k < 20000; ++k) out.push_back(sensor.measure(Eigen::VectorXd::Constant(1, 0.5))(0) - 0.5);
    return out;
  };
  const std::vector<double> a = draws(7), b = draws(7), c = draws(8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  double mean = 0, square = 0;
  for (double x : a) mean += x / a.size(), square += x * x / a.size();
  EXPECT_NEAR(mean, 0.0, 4 * sigma / std::sqrt(a.size()));
  EXPECT_NEAR(std::sqrt(square), sigma, 0.03 * sigma);
}

TEST(JointSensor, BadParametersAreRefused) {
  EXPECT_THROW(JointSensor(2, {Eigen::Vector2d(-1, 0), Eigen::Vector2d::Zero(), 0, 1, {}}),
               std::invalid_argument);
  EXPECT_THROW(JointSensor(2, {Eigen::Vector2d::Zero(), Eigen::Vector2d(0, -1), 0, 1, {}}),
               std::invalid_argument);
  EXPECT_THROW(JointSensor(2, {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), -1, 1, {}}),
               std::invalid_argument);
  EXPECT_THROW(JointSensor(2, {Eigen::Vector3d::Zero(), Eigen::Vector2d::Zero(), 0, 1, {}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace lagrange::plant
