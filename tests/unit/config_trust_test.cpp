// Bad input is refused before any work starts (docs/configuration.md,
// "Ranges and bounds"): numbers out of their key's range, scenarios whose
// work (samples, physics steps, memory, log) is past a bound, duplicate
// keys, files that are not regular files of bounded size, URDF documents
// that are not trees. Each case names the key or file, the number and the
// bound, and returns at once (the ctest timeout catches a hang).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/input_file.hpp"
#include "config/key_ranges.hpp"
#include "config/scenario.hpp"
#include "config/work_bounds.hpp"
#include "model/urdf_arm.hpp"
#include "model/urdf_tree.hpp"
#include "support/scenario_text.hpp"
#include "util/error.hpp"

namespace lagrange::config {
namespace {

using testing::errorOf;
using testing::kConfigs;
using testing::readFile;

std::string loadError(const std::string& path) {
  try {
    loadScenario(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

struct Refused {
  std::vector<std::string> overrides;
  std::string message;  // a fragment of the error
};

class OutOfBounds : public ::testing::TestWithParam<Refused> {};

TEST_P(OutOfBounds, IsRefusedWithTheNumberAndTheBound) {
  const std::string error = errorOf(readFile(kConfigs + "/rigid_2dof.yaml"), GetParam().overrides);
  EXPECT_NE(error.find("config: test.yaml: " + GetParam().message), std::string::npos) << "got: " << error;
}

INSTANTIATE_TEST_SUITE_P(
    Ranges, OutOfBounds,
    ::testing::Values(
        // The six inputs that hung, ran nothing or crashed (issue #28).
        Refused{{"controller.kp=1e308"},
                "controller.kp: expected a number > 0 and at most 1e12, got 1e308 (gains beyond 1e12"},
        Refused{{"plant.physics_step=1e-300"},
                "plant.physics_step: expected a number from 1e-7 to 1 s, got 1e-300"},
        Refused{{"duration=1e300"}, "duration: expected a number > 0 and at most 1e9 s, got 1e300"},
        Refused{{"duration=1e9"},
                "duration: duration 1e9 s at plant.publish_rate 1000 Hz is 1e12 samples; at most 1e8 are "
                "allowed"},
        Refused{{"reference.frequency=[1e308, 3]"},
                "reference.frequency: entry 1: expected a number from 0 to 10000 rad/s, got 1e308"},
        Refused{{"lockstep.retransmit_timeout=1e-300"},
                "lockstep.retransmit_timeout: expected a number from 0.001 to 3600 s, got 1e-300"},
        // Ranges of other kinds of keys: integers, list entries, list items, maps by name.
        Refused{{"lockstep.logger_window=100000"},
                "lockstep.logger_window: expected a number from 1 to 10000 ticks, got 100000"},
        Refused{{"controller.kd=[1, 1e13]"},
                "controller.kd: entry 2: expected a number > 0 and at most 1e12"},
        Refused{{"robot.preset=null", "robot.links=[{length: 1e4, com: 0.5, mass: 1, inertia: 0.1}]"},
                "robot.links[0].length: expected a number from 0.0001 to 1000 m, got 10000"},
        Refused{{"faults.channels.all={delay: 3600}"},
                "faults.channels.all.delay: expected a number from 0 to 60 s, got 3600"},
        Refused{{"initial_state.qdot=[1e5, 0]"},
                "initial_state.qdot: entry 1: expected a number from -10000 to 10000 rad/s, got 100000"}));

INSTANTIATE_TEST_SUITE_P(
    Work, OutOfBounds,
    ::testing::Values(
        Refused{{"plant.publish_rate=0.1", "plant.physics_step=1e-7"},
                "plant.physics_step: physics_step 1e-7 s at publish_rate 0.1 Hz is 1e8 physics steps a "
                "sample; at most 100000 are allowed"},
        Refused{{"duration=100000", "plant.physics_step=1e-5"},
                "duration: duration 100000 s at plant.physics_step 1e-5 s is 1e10 physics steps; at most 1e9 "
                "are allowed"},
        Refused{{"duration=50000", "plant.physics_step=1e-4"},
                "duration: duration 50000 s would keep about 12.3 GiB of recorded series in memory (the "
                "logger's samples); at most 4 GiB are allowed"},
        Refused{
            {"duration=12000", "plant.physics_step=1e-4"},
            "duration: duration 12000 s would write a log of about 20.4 GiB; at most 16 GiB are allowed"}));

TEST(WorkBounds, EveryShippedConfigIsFarWithinEveryBound) {
  for (const auto& entry : std::filesystem::directory_iterator(kConfigs)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const Scenario s = loadScenario(entry.path().string());
    const double samples = s.duration * s.plant.publish_rate;
    EXPECT_LT(samples, kMaxSamples / 1000);
    EXPECT_LT(s.substepsPerTick(), kMaxStepsPerSample / 1000);
    EXPECT_LT(s.duration / s.plant.physics_step, kMaxPhysicsSteps / 1000);
    EXPECT_LT(seriesBytes(s), kMaxSeriesBytes / 100);
    EXPECT_LT(samples * logBytesPerSample(s), kMaxLogBytes / 100);
    EXPECT_LE(s.dof(), kMaxJoints / 2);
  }
}

TEST(WorkBounds, AFreeMotionReferenceCountsItsTable) {
  // chain_m1_free_motion: the reference's table (2n doubles every 0.1 ms) outgrows the logger's series.
  Scenario s = loadScenario(kConfigs + "/chain_m1_free_motion.yaml");
  ASSERT_EQ(s.reference.type, model::ReferenceType::kFreeMotion);
  s.duration = 1e4;
  EXPECT_GT(seriesBytes(s), (s.duration + 1.0) / 1e-4 * 16.0 * s.dof());
  try {
    checkWorkBounds(s);
    FAIL() << "1e4 s of free motion were accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("the free_motion reference's table"), std::string::npos) << e.what();
  }
}

TEST(KeyRanges, PathsAreNamedAsTheTableNamesThem) {
  EXPECT_EQ(rangeKey("robot.links[12].mass"), "robot.links[i].mass");
  EXPECT_EQ(rangeKey("controller.stages[0].kp"), "controller.stages[i].kp");
  EXPECT_EQ(rangeKey("faults.channels.PLANT_POSITION.drop"), "faults.channels.NAME.drop");
  EXPECT_EQ(rangeKey("faults.receivers.logger.drop"), "faults.receivers.PROCESS.drop");
  EXPECT_EQ(rangeKey("actuator.initial_state[1].row"), "actuator.initial_state");
  EXPECT_EQ(shortNumber(1e-7), "1e-7");
  EXPECT_EQ(shortNumber(1e12), "1e12");
  EXPECT_EQ(shortNumber(3600), "3600");
}

TEST(KeyRanges, EveryBoundIsFiniteAndOrdered) {
  for (const auto& [key, r] : keyRanges()) {
    SCOPED_TRACE(key);
    EXPECT_TRUE(std::isfinite(r.min) && std::isfinite(r.max));
    EXPECT_LT(r.min, r.max);
    EXPECT_LE(r.max, 1e15) << "a bound this large lets products overflow";
  }
}

TEST(DuplicateKeys, AreRefusedWithBothLines) {
  const std::string base = readFile(kConfigs + "/rigid_2dof.yaml");
  const std::string error = errorOf(base + "duration: 3\n");
  EXPECT_NE(error.find("config: test.yaml: duplicate key 'duration' at line "), std::string::npos) << error;
  EXPECT_NE(error.find("(first at line "), std::string::npos) << error;
  EXPECT_NE(error.find("); expected each key once in a map"), std::string::npos) << error;
  // Nested, and inside a list item.
  EXPECT_NE(errorOf("name: x\nrobot:\n  gravity: 1\n  gravity: 2\n")
                .find("duplicate key 'robot.gravity' at line 4 (first at line 3)"),
            std::string::npos);
  EXPECT_NE(errorOf("name: x\nrobot:\n  links:\n    - {length: 1, mass: 1, length: 2}\n")
                .find("duplicate key 'robot.links[0].length' at line 4 (first at line 4)"),
            std::string::npos);
}

TEST(DuplicateKeys, AnAliasBombIsRefusedQuickly) {
  // Ten aliases of ten aliases of ... : 10^8 nodes described in a few hundred bytes.
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i <= 8; ++i) {
    const std::string prev = "*a" + std::to_string(i - 1);
    text += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [" + prev;
    for (int k = 1; k < 10; ++k) text += ", " + prev;
    text += "]\n";
  }
  const auto start = std::chrono::steady_clock::now();
  const std::string error = errorOf(text);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_NE(error.find("the YAML tree has more than 1000000 nodes (aliases expanded)"), std::string::npos)
      << error;
}

class ScenarioFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("lagrange-trust-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(ScenarioFile, ADirectoryIsNotAScenario) {
  EXPECT_EQ(loadError(dir_.string()),
            "config: '" + dir_.string() + "' is a directory; expected a YAML scenario file (a regular file)");
}

TEST_F(ScenarioFile, ADeviceIsNotReadWhole) {
  EXPECT_EQ(loadError("/dev/zero"),
            "config: '/dev/zero' is a character device; expected a YAML scenario file (a regular file)");
}

TEST_F(ScenarioFile, AFifoIsRefusedWithoutWaitingForAWriter) {
  const std::string fifo = (dir_ / "pipe.yaml").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(loadError(fifo),
            "config: '" + fifo + "' is a FIFO (named pipe); expected a YAML scenario file (a regular file)");
}

TEST_F(ScenarioFile, ALargeFileIsRefusedBeforeItIsRead) {
  const std::string big = (dir_ / "big.yaml").string();
  std::ofstream(big) << "# " << std::string(kMaxScenarioBytes, 'x') << "\n";
  EXPECT_EQ(loadError(big),
            "config: '" + big + "' is larger than 1 MiB; expected a YAML scenario file of at most 1 MiB");
}

TEST_F(ScenarioFile, AUrdfThatIsNotARegularFileIsNamed) {
  std::string text = readFile(kConfigs + "/panda_theorem1.yaml");
  const auto from = text.find("file: ");
  ASSERT_NE(from, std::string::npos);
  text.replace(from, text.find('\n', from) - from, "file: /dev/zero");
  const std::string path = (dir_ / "zero_urdf.yaml").string();
  std::ofstream(path) << text;
  EXPECT_NE(loadError(path).find(
                "robot.urdf.file: '/dev/zero' is a character device; expected a URDF file (a regular file)"),
            std::string::npos)
      << loadError(path);
}

// URDF documents that urdfdom parses but whose joints are not a tree.
std::string urdf(const std::vector<std::array<std::string, 3>>& joints,
                 const std::vector<std::string>& links) {
  std::string xml = "<robot name='r'><link name='base'/>";
  for (const std::string& l : links)
    xml += "<link name='" + l +
           "'><inertial><mass value='1'/><inertia ixx='0.01' iyy='0.01' izz='0.01' ixy='0' ixz='0' "
           "iyz='0'/></inertial></link>";
  for (const auto& [name, parent, child] : joints)
    xml += "<joint name='" + name + "' type='continuous'><parent link='" + parent + "'/><child link='" +
           child + "'/><axis xyz='0 0 1'/></joint>";
  return xml + "</robot>";
}

std::string buildError(const std::string& xml, const std::string& tip) {
  try {
    model::UrdfArm::build({xml, "arm.urdf", "base", tip, 9.81});
  } catch (const lagrange::Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(UrdfTree, ALoopOfJointsIsNamed) {
  EXPECT_EQ(buildError(urdf({{"j1", "base", "a"}, {"j2", "a", "b"}, {"j3", "b", "a"}}, {"a", "b"}), "b"),
            "arm.urdf: link 'a' is the child of two joints ('j1' and 'j3'); expected a tree (each link the "
            "child of at most one joint, no loops)");
}

TEST(UrdfTree, ALinkWithTwoParentsIsNamed) {
  EXPECT_EQ(buildError(urdf({{"j1", "base", "a"}, {"j2", "base", "b"}, {"j3", "a", "c"}, {"j4", "b", "c"}},
                            {"a", "b", "c"}),
                       "c"),
            "arm.urdf: link 'c' is the child of two joints ('j3' and 'j4'); expected a tree (each link the "
            "child of at most one joint, no loops)");
}

TEST(UrdfTree, ALoopHangingFromNothingIsNamed) {
  EXPECT_EQ(buildError(urdf({{"j1", "base", "a"}, {"j2", "x", "y"}, {"j3", "y", "x"}}, {"a", "x", "y"}), "x"),
            "arm.urdf: link 'x' cannot be reached from the root link 'base' (its joints form a loop); "
            "expected a tree");
}

TEST(UrdfTree, TooManyJointsAreRefused) {
  std::vector<std::array<std::string, 3>> joints;
  std::vector<std::string> links;
  for (int i = 0; i <= model::kMaxUrdfJoints; ++i) {
    links.push_back("l" + std::to_string(i));
    joints.push_back({"j" + std::to_string(i), i == 0 ? "base" : "l" + std::to_string(i - 1), links.back()});
  }
  EXPECT_EQ(buildError(urdf(joints, links), "l3"), "arm.urdf: 1001 joints; at most 1000 are allowed");
}

TEST(UrdfTree, AChainLongerThanTheJointBoundIsRefusedByTheScenario) {
  std::vector<std::array<std::string, 3>> joints;
  std::vector<std::string> links;
  for (int i = 0; i <= kMaxJoints; ++i) {
    links.push_back("l" + std::to_string(i));
    joints.push_back({"j" + std::to_string(i), i == 0 ? "base" : "l" + std::to_string(i - 1), links.back()});
  }
  YAML::Emitter xml;
  xml << YAML::DoubleQuoted << urdf(joints, links);
  const std::string text = "name: long\nduration: 1\nrobot:\n  urdf:\n    xml: " + std::string(xml.c_str()) +
                           "\n    base_link: base\n    tip_link: l16\n";
  EXPECT_NE(errorOf(text).find("robot.urdf: robot.urdf.xml: the chain from 'base' to 'l16' has 17 moving "
                               "joints; at most 16 are allowed"),
            std::string::npos)
      << errorOf(text);
}

}  // namespace
}  // namespace lagrange::config
