// The plant's joint keys (plant.joint_damping, joint_friction, urdf_dynamics,
// rotor_*, joint_limits) and actuator.saturation: urdf, read into the
// damping, friction and stops the plant builds, and refused when wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "config/scenario.hpp"
#include "plant/scenario_plant.hpp"
#include "support/configs.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::testing {
namespace {

const std::string kPanda = kConfigs + "/panda_theorem1.yaml";

// The error a scenario file is refused with (its URDF read from its folder).
std::string fileErrorOf(const std::string& path, const std::vector<std::string>& overrides) {
  try {
    config::loadScenario(path, overrides);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PlantKeys, NoneByDefault) {
  for (const std::string& config : {kRigid, kPanda}) {
    const plant::JointPhysics p = plant::jointPhysicsFor(config::loadScenario(config));
    EXPECT_EQ(p.damping.size() + p.friction.size() + p.lower.size() + p.rotor_damping.size(), 0) << config;
  }
}

TEST(PlantKeys, AChainsLossesPerJointOrOneForAll) {
  const plant::JointPhysics p = plant::jointPhysicsFor(
      config::loadScenario(kRigid, {"plant.joint_damping=[0.5, 0.25]", "plant.joint_friction=0.3"}));
  EXPECT_EQ(p.damping, Eigen::Vector2d(0.5, 0.25));
  EXPECT_EQ(p.friction, Eigen::Vector2d(0.3, 0.3));
  // Written back as read.
  const config::Scenario again = config::parseScenario(
      config::toYaml(config::loadScenario(kRigid, {"plant.joint_friction=0.3"})), "resolved.yaml");
  EXPECT_EQ(*again.plant.joint_friction, Eigen::Vector2d(0.3, 0.3));
  EXPECT_FALSE(again.plant.joint_damping.has_value());
}

TEST(PlantKeys, TheUrdfsDynamicsOnlyWhenAskedAndOverriddenByTheKeys) {
  const plant::JointPhysics urdf =
      plant::jointPhysicsFor(config::loadScenario(kPanda, {"plant.urdf_dynamics=true"}));
  ASSERT_EQ(urdf.damping.size(), 7);
  EXPECT_EQ(urdf.damping, Eigen::VectorXd::Constant(7, 0.003));  // robots/panda.urdf
  EXPECT_EQ(urdf.friction, Eigen::VectorXd::Zero(7));
  const plant::JointPhysics overridden = plant::jointPhysicsFor(
      config::loadScenario(kPanda, {"plant.urdf_dynamics=true", "plant.joint_friction=0.5"}));
  EXPECT_EQ(overridden.damping, Eigen::VectorXd::Constant(7, 0.003));
  EXPECT_EQ(overridden.friction, Eigen::VectorXd::Constant(7, 0.5));
}

TEST(PlantKeys, TheUrdfsLimitsAsStopsAndItsEffortsAsTheSaturation) {
  const config::Scenario s =
      config::loadScenario(kPanda, {"plant.joint_limits=true", "actuator.saturation=urdf"});
  const plant::JointPhysics p = plant::jointPhysicsFor(s);
  ASSERT_EQ(p.lower.size(), 7);
  EXPECT_EQ(p.lower(3), -3.0718);  // panda_joint4's <limit lower upper>
  EXPECT_EQ(p.upper(3), -0.0698);
  ASSERT_TRUE(s.actuator.saturation.has_value());
  EXPECT_EQ(*s.actuator.saturation,
            (Eigen::VectorXd(7) << 87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0).finished());
  // config.resolved.yaml holds the numbers.
  const std::string resolved = config::toYaml(s);
  EXPECT_NE(resolved.find("saturation: [87, 87, 87, 87, 12, 12, 12]"), std::string::npos) << resolved;
}

TEST(PlantKeys, AUrdfLimitOfZeroToZeroIsNoStop) {
  // robots/double_pendulum.urdf writes <limit lower="0" upper="0">: no limits, not a locked joint.
  const config::Scenario s =
      config::loadScenario(kConfigs + "/double_pendulum_flexible.yaml", {"plant.joint_limits=true"});
  const plant::JointPhysics p = plant::jointPhysicsFor(s);
  ASSERT_EQ(p.lower.size(), 2);
  EXPECT_TRUE(std::isinf(p.lower(0)) && std::isinf(p.upper(0)) && std::isinf(p.lower(1)) &&
              std::isinf(p.upper(1)));
}

TEST(PlantKeys, RefusesWhatDoesNotFitTheArm) {
  const std::string rigid = readFile(kRigid);
  EXPECT_NE(errorOf(rigid, {"plant.joint_damping=-0.1"}).find("plant.joint_damping: expected numbers >= 0"),
            std::string::npos)
      << errorOf(rigid, {"plant.joint_damping=-0.1"});
  EXPECT_NE(errorOf(rigid, {"plant.joint_friction=[1, 2, 3]"}).find("plant.joint_friction"),
            std::string::npos);
  EXPECT_NE(errorOf(rigid, {"plant.joint_friction=1e7"}).find("plant.joint_friction"), std::string::npos);
  EXPECT_NE(errorOf(rigid, {"plant.rotor_damping=0.1"}).find("only an arm with robot.flexible has rotors"),
            std::string::npos);
  EXPECT_NE(errorOf(rigid, {"plant.urdf_dynamics=true"}).find("plant.urdf_dynamics: the arm has no URDF"),
            std::string::npos);
  EXPECT_NE(errorOf(rigid, {"plant.joint_limits=true"}).find("plant.joint_limits: the arm has no URDF"),
            std::string::npos);
  EXPECT_NE(errorOf(rigid, {"actuator.saturation=urdf"}).find("actuator.saturation: `urdf`"),
            std::string::npos)
      << errorOf(rigid, {"actuator.saturation=urdf"});
  EXPECT_NE(errorOf(rigid, {"actuator.saturation=urdff"}).find("actuator.saturation"), std::string::npos);
  const std::string outside =
      fileErrorOf(kPanda, {"plant.joint_limits=true", "initial_state.q=[0, 0, 0, 0, 0, 0, 0]"});
  EXPECT_NE(outside.find("initial_state.q[3] = 0.000000 is outside joint 'panda_joint4''s <limit"),
            std::string::npos)
      << outside;
}

TEST(PlantKeys, RefusesAUrdfWhoseDynamicsAreNegativeOnlyWhenTheyAreUsed) {
  std::string xml = readFile(kConfigs + "/../robots/panda.urdf");
  const size_t at = xml.find("damping=\"0.003\"");
  ASSERT_NE(at, std::string::npos);
  xml.replace(at, 15, "damping=\"-1\"");
  const std::string dir = ::testing::TempDir() + "/plant_keys";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/bad.urdf") << xml;
  const std::vector<std::string> urdf = {"robot.urdf.file=" + dir + "/bad.urdf"};
  EXPECT_EQ(fileErrorOf(kPanda, urdf), "(no error)");
  std::vector<std::string> used = urdf;
  used.push_back("plant.urdf_dynamics=true");
  EXPECT_NE(fileErrorOf(kPanda, used).find("joint 'panda_joint1' of the URDF has <dynamics damping=-1"),
            std::string::npos)
      << fileErrorOf(kPanda, used);
}

}  // namespace
}  // namespace lagrange::testing
