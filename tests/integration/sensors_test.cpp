// The sensors in the plant's measurement path (sensors.*): the controller
// sees the readings -- joint angles quantised, noisy, a sample late; a
// tachometer's rates only when declared, and only by a controller that
// declares it needs them; motor angles of elastic joints -- while PLANT_TRUTH
// keeps the true values; lockstep and in-process compute the same run bit for
// bit with the noise on, and the log replays exactly through every component
// (the plant draws the same noise again).
#include <gtest/gtest.h>

#include <cmath>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/realtime_run.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

constexpr double kCounts = 4096, kSigma = 1e-4;
const std::string kSensors =
    "--set duration=3 --set 'sensors={seed: 3, position: {counts_per_revolution: 4096, "
    "noise_sigma: 1.0e-4, delay: 1}}'";

TEST(Sensors, ReadingsAreQuantisedNoisyAndLateAndEveryWiringAgrees) {
  const std::string config = kConfigs + "/rigid_2dof.yaml";
  const std::string lockstep = freshDir("sensors-lockstep"), inproc = freshDir("sensors-inproc");
  ASSERT_EQ(runScenario(config, lockstep, "-q --mode lockstep " + kSensors).exit_code, 0);
  ASSERT_EQ(runScenario(config, inproc, "-q --mode inproc " + kSensors).exit_code, 0);

  const auto truth = readTruth(lockstep + "/run.lcm");
  const auto read = readPositions(lockstep + "/run.lcm");
  ASSERT_EQ(truth.size(), 3001u);
  ASSERT_EQ(read.size(), 3001u);
  // The sensor acted: every reading is a whole number of counts, within a
  // count and a few sigma below the angle of the tick before, and most differ
  // from the true angle of their own tick.
  const double step = 2 * M_PI / kCounts;
  size_t differs = 0;
  for (size_t k = 1; k < truth.size(); ++k) {
    const std::vector<double>& q = read.at(static_cast<long long>(k));
    for (size_t j = 0; j < q.size(); ++j) {
      EXPECT_NEAR(q[j] / step, std::round(q[j] / step), 1e-6) << "tick " << k;
      const double late = truth[k - 1].q(static_cast<Eigen::Index>(j));
      EXPECT_LE(q[j], late + 6 * kSigma) << "tick " << k;
      EXPECT_GE(q[j], late - step - 6 * kSigma) << "tick " << k;
      differs += q[j] != truth[k].q(static_cast<Eigen::Index>(j));
    }
  }
  EXPECT_GT(differs, 5900u);
  // The controller still brings the true angles within a few counts.
  const auto j = readSummary(lockstep);
  EXPECT_LT(j["tracking"]["final_error"].get<double>(), 3 * step) << j["tracking"].dump();

  // In-process: the same readings, trajectory and commands, bit for bit.
  const auto truth_inproc = readTruth(inproc + "/run.lcm");
  ASSERT_EQ(truth_inproc.size(), truth.size());
  for (size_t k = 0; k < truth.size(); ++k) ASSERT_EQ(truth[k].q, truth_inproc[k].q) << "tick " << k;
  EXPECT_EQ(read, readPositions(inproc + "/run.lcm"));
  EXPECT_EQ(readCommands(lockstep + "/run.lcm"), readCommands(inproc + "/run.lcm"));

  for (const std::string component : {"controller", "actuator", "plant"}) {
    const RunResult replay = lagrange("replay " + quote(lockstep + "/run.lcm") + " --component " + component);
    EXPECT_EQ(replay.exit_code, 0) << component << ": " << replay.output;
    EXPECT_NE(replay.output.find("reproduced all 3001 recorded outputs"), std::string::npos) << replay.output;
  }
}

// A velocity sensor: PD+ gets the tachometer's noisy, late rates on
// PLANT_RATE (PLANT_TRUTH keeps the true ones), lockstep and in-process agree
// bit for bit, and the log replays through the controller (which reads the
// recorded rates) and the plant (which draws them again).
const std::string kPdPlus =
    "--set duration=3 --set 'controller={type: pd_plus, kp: [150.0, 10.0], kd: [15.0, 1.0]}' "
    "--set 'sensors={seed: 5, position: {counts_per_revolution: 65536}, velocity: {noise_sigma: 0.01, "
    "delay: 1}}'";

TEST(Sensors, AVelocitySensorFeedsPdPlusItsNoisyLateRatesInEveryWiring) {
  const std::string config = kConfigs + "/rigid_2dof.yaml";
  const std::string lockstep = freshDir("rates-lockstep"), inproc = freshDir("rates-inproc");
  ASSERT_EQ(runScenario(config, lockstep, "-q --mode lockstep " + kPdPlus).exit_code, 0);
  ASSERT_EQ(runScenario(config, inproc, "-q --mode inproc " + kPdPlus).exit_code, 0);
  const auto truth = readTruth(lockstep + "/run.lcm");
  const auto rates = readRates(lockstep + "/run.lcm");
  ASSERT_EQ(rates.size(), truth.size());
  // Each rate reading is the true rate of the tick before plus noise of sigma
  // 0.01 rad/s: within 6 sigma, and the spread about it near sigma.
  double sum_sq = 0.0;
  size_t count = 0;
  for (size_t k = 1; k < truth.size(); ++k)
    for (size_t j = 0; j < 2; ++j) {
      const double noise =
          rates.at(static_cast<long long>(k))[j] - truth[k - 1].qdot(static_cast<Eigen::Index>(j));
      EXPECT_LT(std::abs(noise), 0.06) << "tick " << k;
      sum_sq += noise * noise, ++count;
    }
  EXPECT_NEAR(std::sqrt(sum_sq / static_cast<double>(count)), 0.01, 0.001);
  const auto j = readSummary(lockstep);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();

  EXPECT_EQ(rates, readRates(inproc + "/run.lcm"));
  EXPECT_EQ(readCommands(lockstep + "/run.lcm"), readCommands(inproc + "/run.lcm"));
  for (const std::string component : {"controller", "plant"}) {
    const RunResult replay = lagrange("replay " + quote(lockstep + "/run.lcm") + " --component " + component);
    EXPECT_EQ(replay.exit_code, 0) << component << ": " << replay.output;
    EXPECT_NE(replay.output.find("reproduced all 3001 recorded outputs"), std::string::npos) << replay.output;
  }
}

// Realtime pairs each position with the rate of its own tick, so the log
// replays there too (the command's position tick names its rate).
TEST(Sensors, AVelocityControllerRunsInRealtimeAndReplays) {
  const std::string dir = freshDir("rates-realtime");
  const RunResult run = runScenario(kConfigs + "/rigid_2dof.yaml", dir,
                                    "-q --mode realtime --set duration=2 "
                                    "--set 'controller={type: pd_plus, kp: [150.0, 10.0], kd: [15.0, 1.0]}' "
                                    "--set 'sensors={velocity: {noise_sigma: 0.01}}'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  expectTheArmTrackedAndEveryCommandIsAccountedFor(dir);
  const RunResult replay = lagrange("replay " + quote(dir + "/run.lcm") + " --component controller");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("reproduced all"), std::string::npos) << replay.output;
}

// The paper's controller and the observer-based baselines never receive a
// velocity: declaring a noisy tachometer changes none of their commands (the
// position sensor's draws are its own, so its readings are the same too).
TEST(Sensors, PositionOnlyControllersIgnoreADeclaredVelocitySensor) {
  const std::string config = kConfigs + "/rigid_2dof.yaml";
  const std::string position = "position: {counts_per_revolution: 4096, noise_sigma: 1.0e-4}";
  for (const std::string& controller :
       {std::string(),
        std::string("--set 'controller={type: nicosia_tomei, kp: [150.0, 10.0], kd: [15.0, 1.0], "
                    "lp: [2500.0, 2500.0], ld: [100.0, 100.0]}'"),
        std::string("--set 'controller={type: berghuis_nijmeijer, kp: [150.0, 10.0], kd: [15.0, 1.0], "
                    "lambda: [10.0, 10.0], lp: [2500.0, 2500.0], ld: [100.0, 100.0]}'")}) {
    const std::string without = freshDir("rates-without"), with = freshDir("rates-with");
    const std::string common = "-q --mode inproc --set duration=1 " + controller;
    ASSERT_EQ(runScenario(config, without, common + " --set 'sensors={" + position + "}'").exit_code, 0);
    ASSERT_EQ(runScenario(config, with,
                          common + " --set 'sensors={" + position + ", velocity: {noise_sigma: 0.5}}'")
                  .exit_code,
              0);
    EXPECT_EQ(readRates(without + "/run.lcm").size(), 0u) << controller;
    EXPECT_EQ(readRates(with + "/run.lcm").size(), 1001u) << controller;  // the sensor is there
    EXPECT_EQ(readPositions(without + "/run.lcm"), readPositions(with + "/run.lcm")) << controller;
    EXPECT_EQ(readCommands(without + "/run.lcm"), readCommands(with + "/run.lcm")) << controller;
  }
}

// A motor-angle sensor on flexible joints: PLANT_MOTOR carries the encoder's
// noisy, quantised q2, the controller acts on it, and the log replays.
TEST(Sensors, AMotorSensorQuantisesTheMotorAnglesTheFlexibleControllerReads) {
  const std::string config = kConfigs + "/flexible_2dof.yaml";
  const std::string exact = freshDir("motor-exact"), read = freshDir("motor-read");
  ASSERT_EQ(runScenario(config, exact, "-q --mode inproc --set duration=1").exit_code, 0);
  ASSERT_EQ(
      runScenario(config, read,
                  "-q --mode inproc --set duration=1 "
                  "--set 'sensors={seed: 2, motor: {counts_per_revolution: 65536, noise_sigma: 1.0e-4}}'")
          .exit_code,
      0);
  const auto truth = readReadings(exact + "/run.lcm", "PLANT_MOTOR", &lagrange::plant_motor_t::q);
  const auto motor = readReadings(read + "/run.lcm", "PLANT_MOTOR", &lagrange::plant_motor_t::q);
  ASSERT_EQ(motor.size(), 1001u);
  // Tick 0 starts from the same state: the reading is the true q2(0) plus
  // noise, floored to a count.
  const double step = 2 * M_PI / 65536;
  for (size_t j = 0; j < 2; ++j) {
    const double reading = motor.at(0)[j], q2 = truth.at(0)[j];
    EXPECT_NEAR(reading / step, std::round(reading / step), 1e-6);
    EXPECT_NE(reading, q2);
    EXPECT_LT(std::abs(reading - q2), step + 6e-4);
  }
  EXPECT_NE(readCommands(exact + "/run.lcm"), readCommands(read + "/run.lcm"));  // the controller read it
  for (const std::string component : {"controller", "plant"}) {
    const RunResult replay = lagrange("replay " + quote(read + "/run.lcm") + " --component " + component);
    EXPECT_EQ(replay.exit_code, 0) << component << ": " << replay.output;
    EXPECT_NE(replay.output.find("reproduced all 1001 recorded outputs"), std::string::npos) << replay.output;
  }
}

}  // namespace
}  // namespace lagrange::testing
