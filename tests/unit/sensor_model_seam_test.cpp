// The sensor-model seam (plant/sensor_models.hpp) with a model only this file
// knows: its keys are read, checked and written back by config, and every
// sensor whose section gives them applies its effect, after the delay and
// before the noise and the quantisation.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "config/scenario.hpp"
#include "plant/scenario_plant.hpp"
#include "plant/sensor_models.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::plant {
namespace {

// scale * value + offset, per joint: a miscalibrated sensor.
class ScaleAndOffset final : public SensorEffect {
 public:
  ScaleAndOffset(Eigen::VectorXd scale, Eigen::VectorXd offset)
      : scale_(std::move(scale)), offset_(std::move(offset)) {}
  Eigen::VectorXd apply(const Eigen::VectorXd& value) override {
    return scale_.cwiseProduct(value) + offset_;
  }

 private:
  const Eigen::VectorXd scale_, offset_;
};

const bool calibration_registered = registerSensorModel(
    {"test_calibration",
     {{"test_scale", true, "gain of the sensor [1]"}, {"test_offset", false, "offset [rad, or rad/s]"}},
     [](const SensorModelParams& p, int, uint64_t) {
       return std::make_unique<ScaleAndOffset>(p.at("test_scale"), p.at("test_offset"));
     }});

config::Scenario rigid(const std::vector<std::string>& overrides) {
  return config::parseScenario(testing::readFile(testing::kRigid), "rigid_2dof.yaml", overrides);
}

TEST(SensorModelSeam, ATestOnlyModelIsReadWrittenAndApplied) {
  ASSERT_TRUE(calibration_registered);
  const config::Scenario s =
      rigid({"sensors={position: {test_scale: [2, 1], test_offset: [0.1, -0.2]}, "
             "velocity: {noise_sigma: 0}}"});
  ScenarioSensors sensors = sensorsFor(s);
  const Eigen::Vector2d q(0.3, -1.1), qdot(0.7, 2.0);
  EXPECT_EQ(sensors.position.measure(q), Eigen::Vector2d(2 * 0.3 + 0.1, -1.1 - 0.2));
  ASSERT_TRUE(sensors.velocity.has_value());
  EXPECT_TRUE(sensors.velocity->ideal());  // its section names no model: untouched
  EXPECT_EQ(sensors.velocity->measure(qdot), qdot);
  // config.resolved.yaml carries the keys, and reads back the same sensors.
  const config::Scenario again = config::parseScenario(config::toYaml(s), "resolved", {});
  EXPECT_EQ(again.sensors->position.model_params, s.sensors->position.model_params);
  EXPECT_NE(config::toYaml(s).find("test_offset"), std::string::npos);
  EXPECT_EQ(config::toYaml(again), config::toYaml(s));
}

TEST(SensorModelSeam, TheEffectActsAfterTheDelayAndBeforeTheQuantisation) {
  const config::Scenario s =
      rigid({"sensors={position: {test_scale: 1, test_offset: [0.004, 0], delay: 1, "
             "counts_per_revolution: [1000, 0]}}"});
  ScenarioSensors sensors = sensorsFor(s);
  const double step = 2 * M_PI / 1000;
  const Eigen::Vector2d q0(0.005, 0.5), q1(1.0, 0.6);
  // Tick 0 reads q0 (held before tick d); tick 1 reads q0 still (one sample late).
  for (const Eigen::Vector2d& q : {q0, q1}) {
    const Eigen::VectorXd reading = sensors.position.measure(q);
    EXPECT_EQ(reading(0), std::floor((q0(0) + 0.004) / step) * step);  // offset, then the encoder's floor
    EXPECT_EQ(reading(1), q0(1));
  }
  EXPECT_GT(std::floor((q0(0) + 0.004) / step), 0.0);  // the offset crossed a count: order matters here
}

TEST(SensorModelSeam, ItsKeysAreCheckedLikeASensorsOwn) {
  const std::string half =
      testing::errorOf(testing::readFile(testing::kRigid), {"sensors={position: {test_offset: [0.1, 0]}}"});
  EXPECT_NE(
      half.find(
          "sensors.position.test_scale: missing; sensor model test_calibration takes its keys together"),
      std::string::npos)
      << half;
  EXPECT_THROW(rigid({"sensors={position: {test_scale: [1, 1, 1], test_offset: 0}}"}), config::ConfigError);
  EXPECT_THROW(rigid({"sensors={position: {test_scale: [1, -1], test_offset: 0}}"}), config::ConfigError);
  // Registrations close once a sensor's keys were read: a late one would be
  // missing from what was read before. (A key a sensor has of its own, as
  // delay, is refused at registration too; registration is closed by now.)
  EXPECT_THROW(registerSensorModel({"test_late",
                                    {{"test_late", false, ""}},
                                    [](const SensorModelParams&, int, uint64_t) { return nullptr; }}),
               std::logic_error);
}

}  // namespace
}  // namespace lagrange::plant
