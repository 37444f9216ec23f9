// Scenario loading: every shipped config loads; bad input is an error that
// names the key and what was expected; the resolved YAML round-trips exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/scenario.hpp"
#include "controller/paper_section.hpp"
#include "model/joint_springs.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::config {
namespace {

using testing::errorOf;
using testing::kConfigs;
using testing::readFile;

TEST(Scenario, EveryShippedConfigLoadsAndRoundTrips) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kConfigs)) {
    if (entry.path().extension() != ".yaml") continue;
    ++count;
    const Scenario s = loadScenario(entry.path().string());
    const Scenario again = parseScenario(toYaml(s), "resolved");
    EXPECT_EQ(toYaml(again), toYaml(s)) << entry.path();
    if (controller::isPaperType(s.controller.type)) {
      EXPECT_EQ(controller::paperSettings(again).gains.kp, controller::paperSettings(s).gains.kp);
    }
    EXPECT_EQ(again.initial_state.q, s.initial_state.q);
    EXPECT_EQ(again.reference.offset, s.reference.offset);  // bit-exact doubles
  }
  EXPECT_GE(count, 3);
}

TEST(Scenario, DefaultsAndOverrides) {
  const std::string base = readFile(kConfigs + "/rigid_2dof.yaml");
  const Scenario s =
      parseScenario(base, "rigid_2dof.yaml", {"controller.kp=[50, 7]", "duration=2", "controller.a=300"});
  EXPECT_EQ(controller::paperSettings(s).gains.kp, Eigen::Vector2d(50, 7));
  EXPECT_EQ(controller::paperSettings(s).gains.a,
            Eigen::Vector2d(300, 300));  // a scalar applies to every joint
  EXPECT_EQ(s.duration, 2.0);
  EXPECT_EQ(s.lastTick(), 2000);
  EXPECT_EQ(s.substepsPerTick(), 40);                   // 1 ms ticks of 25 us physics steps
  EXPECT_DOUBLE_EQ(s.robot.links[1].inertia, 0.01616);  // the Pelican preset
}

struct BadCase {
  std::vector<std::string> overrides;
  std::string fragment;
};

class BadScenario : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScenario, NamesTheKeyAndWhatWasExpected) {
  const std::string base = readFile(kConfigs + "/rigid_2dof.yaml");
  const std::string error = errorOf(base, GetParam().overrides);
  EXPECT_NE(error.find(GetParam().fragment), std::string::npos) << "got: " << error;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadScenario,
    ::testing::Values(
        BadCase{{"controller.kpp=3"}, "controller.kpp: unknown key"},
        BadCase{
            {"robot.preset=null", "robot.links=[{length: 1, com: 0.5, mass: 1, inertia: 0.1, colour: red}]"},
            "robot.links[0].colour: unknown key"},
        BadCase{{"robot.links=[{length: 1, com: 0.5, mass: 1, inertia: 0.1}]"},
                "give exactly one of robot.preset (pelican), robot.links or robot.urdf"},
        BadCase{{"robot.preset=null", "robot.links=[{length: 1, com: 0.5, mass: 0, inertia: 0.1}]"},
                "robot.links[0].mass: expected a positive number"},
        BadCase{{"controller.kp=abc"}, "controller.kp: expected a list of 2 positive numbers"},
        BadCase{{"controller.kd=[-1, 2]"}, "controller.kd: entry 1: expected a positive number, got '-1'"},
        BadCase{{"controller.a=0"}, "controller.a: expected a list of 2 positive numbers"},
        BadCase{{"initial_state.q=[1, 2, 3]"}, "initial_state.q: expected a list of 2 numbers"},
        BadCase{{"reference.alpha=[1]"}, "reference.alpha: expected a list of 2 positive numbers"},
        BadCase{{"duration=-1"}, "duration: expected a positive number, got '-1'"},
        BadCase{{"duration=ten"}, "duration: expected a finite number, got 'ten'"},
        BadCase{{"plant.physics_step=0.0003"}, "must be a whole multiple of physics_step"},
        BadCase{{"mode=warp"}, "mode: unknown mode 'warp'; expected: lockstep, realtime or inproc"},
        BadCase{{"controller.type=pid"}, "controller.type: unknown controller type 'pid'"},
        BadCase{{"reference.type=square"}, "reference.type: unknown reference type 'square'"},
        BadCase{{"robot.preset=puma"}, "robot.preset: unknown preset 'puma'"},
        BadCase{{"actuator.saturation=[1, 0]"}, "actuator.saturation: entry 2"},
        BadCase{{"controller.kp"}, "--set 'controller.kp': expected key=value"},
        BadCase{{"actuator.order=1"}, "controller.type: the theorem1 controller drives torque directly"},
        BadCase{{"actuator.order=5"}, "actuator.order: expected an integrator-chain order from 0"},
        BadCase{{"actuator.rate=1500"}, "actuator.rate: expected a whole multiple of plant.publish_rate"},
        BadCase{{"actuator.rate=500"}, "actuator.rate: expected a whole multiple of plant.publish_rate"},
        BadCase{{"actuator.rate=0"}, "actuator.rate: expected a positive number"},
        BadCase{{"actuator.rate=3000"},
                "actuator.rate: the actuator period 1/rate must be a whole multiple of"},
        BadCase{{"controller.type=cascaded"}, "the cascaded controller needs an integrator chain"},
        BadCase{{"controller.type=cascaded", "actuator.order=2",
                 "controller.stages=[{kp: 1, kd: 1, a: 1, b: 1}]"},
                "controller.stages: expected a list of 2 stages"},
        BadCase{{"controller.type=cascaded", "actuator.order=1",
                 "controller.stages=[{kp: 1, kd: -1, a: 1, b: 1}]"},
                "controller.stages[0].kd: expected a list of 2 positive numbers"},
        BadCase{{"controller.type=cascaded", "actuator.order=1",
                 "controller.stages=[{kp: 1, kd: 1, a: 1, b: 1, c: 2}]"},
                "controller.stages[0].c: unknown key"},
        BadCase{{"controller.type=cascaded", "actuator.order=1",
                 "controller.stages=[{kp: 1, kd: 1, a: 1, b: 1}]", "actuator.initial_state=[[1, 2, 3]]"},
                "actuator.initial_state[0].row: expected a list of 2 numbers"},
        BadCase{{"controller.stages=[{kp: 1, kd: 1, a: 1, b: 1}]"},
                "only the cascaded and flexible controllers have stages"},
        // The known keys come from the key table, per variant of the section.
        BadCase{{"reference.initial_q=[0, 0]"}, "reference.initial_q: unknown key"},
        BadCase{{"reference.initial_q=[0, 0]"}, "; initial_q is a key of reference.type free_motion only"},
        BadCase{{"controller={type: external, command: [true], stages: []}"},
                "controller.stages: unknown key"},
        BadCase{
            {"controller={type: external, command: [true], kp: 1}"},
            "; kp is a key of the paper's controllers (controller.type theorem1, cascaded, flexible) and of "
            "the baselines that declare it"},
        BadCase{{"controller.lp=3"}, "; lp is a key of the baselines that declare it"},
        BadCase{{"faults.channels.PLANT_RATES={drop: 0.1}"},
                "unknown channel; expected all, PLANT_POSITION, PLANT_TRUTH, PLANT_MOTOR, PLANT_RATE,"}));

// docs/configuration.md names PLANT_RATE among the channels faults can be
// injected on; the reader once refused it.
TEST(Scenario, FaultsOnTheRateChannelAreAccepted) {
  const std::string base = readFile(kConfigs + "/rigid_2dof.yaml");
  const Scenario s =
      parseScenario(base, "rigid_2dof.yaml",
                    {"sensors.velocity={noise_sigma: 0}", "faults.channels.PLANT_RATE={drop: 0.25}"});
  ASSERT_EQ(s.faults.channels.count("PLANT_RATE"), 1u);
  EXPECT_EQ(s.faults.channels.at("PLANT_RATE").drop, 0.25);
}

TEST(Scenario, MissingKeyIsNamed) {
  std::string text = readFile(kConfigs + "/rigid_2dof.yaml");
  const auto pos = text.find("  kp:");
  text.erase(pos, text.find('\n', pos) - pos + 1);
  EXPECT_NE(errorOf(text).find("controller.kp: missing; expected a list of 2 positive numbers"),
            std::string::npos)
      << errorOf(text);
}

TEST(Scenario, MalformedYamlGivesTheLine) {
  const std::string error = errorOf("name: x\nduration: [1, 2\nrobot: {}\n");
  EXPECT_NE(error.find("malformed YAML at line"), std::string::npos) << error;
}

TEST(Scenario, UnreadableFileIsNamed) {
  try {
    loadScenario("/nonexistent/x.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read '/nonexistent/x.yaml'"), std::string::npos);
  }
}

// Flexible joints (robot.flexible, controller type flexible): bad input is
// named before anything starts.
class BadFlexibleScenario : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadFlexibleScenario, NamesTheKeyAndWhatWasExpected) {
  const std::string base = readFile(kConfigs + "/flexible_2dof.yaml");
  const std::string error = errorOf(base, GetParam().overrides);
  EXPECT_NE(error.find(GetParam().fragment), std::string::npos) << "got: " << error;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadFlexibleScenario,
    ::testing::Values(
        BadCase{{"robot.flexible.stiffness=[100, 0]"},
                "robot.flexible.stiffness: entry 2: expected a positive number, got '0'"},
        BadCase{{"robot.flexible.stiffness=[100, -30]"},
                "robot.flexible.stiffness: entry 2: expected a positive"},
        BadCase{{"robot.flexible.rotor_inertia=[0.05, 0]"},
                "robot.flexible.rotor_inertia: entry 2: expected a positive number"},
        BadCase{{"robot.flexible.rotor_inertia=-1"},
                "robot.flexible.rotor_inertia: expected a list of 2 positive"},
        BadCase{{"robot.flexible.rate_sensor=maybe"}, "robot.flexible.rate_sensor: expected true or false"},
        BadCase{{"controller.motor_rate=null"},
                "controller.motor_rate: missing; the paper does not say where q2'"},
        BadCase{{"controller.motor_rate=observer"}, "controller.motor_rate: unknown choice 'observer'"},
        BadCase{{"robot.flexible.rate_sensor=false"},
                "controller.motor_rate: measured needs a motor rate sensor"},
        BadCase{{"controller.motor_rate_pole=300"}, "only motor_rate: filtered has a filter pole"},
        BadCase{{"robot.flexible=null"},
                "controller.type: the flexible controller needs an arm with elastic joints"},
        BadCase{{"controller.type=cascaded"}, "controller.type: robot.flexible has elastic joints"},
        BadCase{{"actuator.order=2"},
                "controller.type: the flexible controller commands the motor torque itself"},
        BadCase{{"controller.stages=[{kp: 1, kd: 1, a: 1, b: 1}]"},
                "controller.stages: expected a list of 2 stages"},
        BadCase{{"initial_state.motor_q=[1, 2, 3]"}, "initial_state.motor_q: expected a list of 2 numbers"}));

TEST(Scenario, MotorStateOnARigidArmIsRefused) {
  const std::string error =
      errorOf(readFile(kConfigs + "/rigid_2dof.yaml"), {"initial_state.motor_q=[0, 0]"});
  EXPECT_NE(error.find("initial_state.motor_q: only an arm with robot.flexible has motors"),
            std::string::npos)
      << error;
}

TEST(Scenario, FlexibleDefaultsHoldTheLinksAtRestAndRoundTrip) {
  const Scenario s = loadScenario(kConfigs + "/flexible_2dof.yaml");
  ASSERT_TRUE(s.flexible.has_value());
  // q2(0) = q + K^-1 g(q): the springs' torque K (q2 - q) balances gravity.
  const model::PlanarChain links(s.robot);
  const Eigen::VectorXd spring =
      s.flexible->params.stiffness.cwiseProduct(s.initial_state.motor_q - s.initial_state.q);
  EXPECT_LT((spring - links.gravity(s.initial_state.q)).norm(), 1e-12);
  // The controller's model is the links with their springs (eq. (46)).
  const auto springs = std::dynamic_pointer_cast<const model::JointSprings>(s.controlModel());
  ASSERT_TRUE(springs);
  EXPECT_EQ(springs->stiffness(), s.flexible->params.stiffness);
  const Scenario again = parseScenario(toYaml(s), "resolved");
  EXPECT_EQ(toYaml(again), toYaml(s));
  EXPECT_EQ(again.initial_state.motor_q, s.initial_state.motor_q);
}

}  // namespace
}  // namespace lagrange::config
