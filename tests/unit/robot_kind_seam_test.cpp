// The robot-kind seam (plant/robot_kinds.hpp) with a kind only this file
// knows: a pendulum described by its own section, robot.test_pendulum. Its
// model and its ODE world are the planar chain's of one link -- what the test
// shows is the seam (read, written, built, run), not a new dynamics.
#include <gtest/gtest.h>

#include <stdexcept>

#include "config/scenario.hpp"
#include "config/yaml_reader.hpp"
#include "model/planar_chain.hpp"
#include "plant/planar_chain_world.hpp"
#include "plant/robot_kinds.hpp"
#include "plant/scenario_plant.hpp"
#include "support/scenario_text.hpp"
#include "wiring/inproc_runner.hpp"

namespace lagrange::plant {
namespace {

struct Pendulum {
  double length = 0.0, mass = 0.0;
};

model::ChainParams chainOf(const std::any& settings, double gravity) {
  const auto& p = std::any_cast<const Pendulum&>(settings);
  return {{{p.length, p.length, p.mass, 1e-4}}, gravity};  // the mass at the tip
}

// The pendulum's section under `key`, its world from `world`.
RobotKind pendulumKind(const std::string& key, std::function<ArmBuilder(const std::any&, double)> world) {
  return {{key,
           [](config::MapReader& section) -> std::any {
             Pendulum p{section.positive("length"), section.positive("mass")};
             section.finish({"length", "mass"});
             return p;
           },
           [](const std::any& settings, double gravity) -> model::RobotModelPtr {
             return std::make_shared<const model::PlanarChain>(chainOf(settings, gravity));
           },
           [](YAML::Emitter& out, const std::any& settings) {
             const auto& p = std::any_cast<const Pendulum&>(settings);
             out << YAML::BeginMap << YAML::Key << "length" << YAML::Value << p.length << YAML::Key << "mass"
                 << YAML::Value << p.mass << YAML::EndMap;
           }},
          std::move(world)};
}

const bool pendulum_registered =
    registerRobotKind(pendulumKind("test_pendulum", [](const std::any& settings, double gravity) {
      return planarChainWorld(chainOf(settings, gravity));
    }));

// The same pendulum described for ODE only, as a kind written before the
// engines had a seam: its builder gives ODE's world and no bodies.
const bool ode_only_registered =
    registerRobotKind(pendulumKind("test_ode_only_pendulum", [](const std::any& settings, double gravity) {
      ArmBuilder b = planarChainWorld(chainOf(settings, gravity));
      b.bodies.reset();
      return b;
    }));

const std::string kScenario = R"(name: pendulum
duration: 3
robot: {gravity: 9.81, test_pendulum: {length: 0.8, mass: 1.5}}
initial_state: {q: [0.6]}
reference: {type: sine, offset: [0.2], amplitude: [0.1], frequency: [1.0]}
controller: {type: theorem1, kp: 60, kd: 6, a: 50, b: 50, initial_filter_state: bumpless}
)";

TEST(RobotKindSeam, ATestOnlyKindIsReadWrittenBuiltAndRun) {
  ASSERT_TRUE(pendulum_registered);
  const config::Scenario s = config::parseScenario(kScenario, "pendulum.yaml");
  ASSERT_EQ(s.dof(), 1);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, 0.3);
  const model::PlanarChain chain({{{0.8, 0.8, 1.5, 1e-4}}, 9.81});
  EXPECT_EQ(s.robotModel()->inertia(q), chain.inertia(q));
  EXPECT_EQ(s.robotModel()->gravity(q), chain.gravity(q));
  // config.resolved.yaml carries the section, and reads back the same arm.
  const std::string resolved = config::toYaml(s);
  EXPECT_NE(resolved.find("test_pendulum"), std::string::npos);
  const config::Scenario again = config::parseScenario(resolved, "resolved");
  EXPECT_EQ(config::toYaml(again), resolved);
  EXPECT_EQ(again.robotModel()->inertia(q), chain.inertia(q));
  // The plant builds its world: unforced, the arm falls under gravity.
  PlantSim sim = plantFor(s);
  EXPECT_EQ(sim.state().q(0), 0.6);
  sim.step(Eigen::VectorXd::Zero(1), 100);
  EXPECT_LT(sim.state().qdot(0), 0.0);
  // And the paper's controller tracks with it, in process.
  const wiring::InProcessOutcome run = wiring::simulateInProcess(s, nullptr, nullptr, nullptr);
  EXPECT_EQ(run.status, "completed");
  EXPECT_LT(run.tracking.final_error, 1e-3) << "initial error 0.4 rad";
}

// Its ArmBuilder gives ODE's world only, no bodies: on MuJoCo the launcher
// refuses the scenario before anything starts, naming the engine.
TEST(RobotKindSeam, AKindDescribedForOdeOnlyIsRefusedOnMujocoBeforeAnythingStarts) {
  ASSERT_TRUE(ode_only_registered);
  std::string text = kScenario;
  text.replace(text.find("test_pendulum"), 13, "test_ode_only_pendulum");
  const config::Scenario s = config::parseScenario(text, "pendulum.yaml", {"plant.engine=mujoco"});
  try {
    checkPlantBuilds(s);
    ADD_FAILURE() << "accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("plant.engine: mujoco cannot simulate this arm"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(checkPlantBuilds(config::parseScenario(text, "pendulum.yaml")));  // on ODE
  EXPECT_NO_THROW(
      checkPlantBuilds(config::parseScenario(kScenario, "pendulum.yaml", {"plant.engine=mujoco"})));
}

TEST(RobotKindSeam, ItsSectionIsCheckedAndItsKeyIsItsOwn) {
  const std::string two_arms = testing::errorOf(kScenario, {"robot.preset=pelican"});
  EXPECT_NE(
      two_arms.find("give exactly one of robot.preset (pelican), robot.links or robot.urdf "
                    "(or a kind built into this program: robot.test_ode_only_pendulum, robot.test_pendulum)"),
      std::string::npos)
      << two_arms;
  const std::string negative = testing::errorOf(kScenario, {"robot.test_pendulum.length=-1"});
  EXPECT_NE(negative.find("robot.test_pendulum.length"), std::string::npos) << negative;
  EXPECT_THROW(config::parseScenario(kScenario, "pendulum.yaml", {"robot.test_pendulum.colour=red"}),
               config::ConfigError);
  // A kind whose every function is there, on a key config reads itself.
  RobotKind taken{{"urdf", [](config::MapReader&) -> std::any { return 0; },
                   [](const std::any&, double) -> model::RobotModelPtr { return nullptr; },
                   [](YAML::Emitter&, const std::any&) {}},
                  [](const std::any&, double) { return ArmBuilder{}; }};
  try {
    registerRobotKind(taken);
    ADD_FAILURE() << "robot.urdf was registered a second time";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("robot.urdf is taken"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lagrange::plant
