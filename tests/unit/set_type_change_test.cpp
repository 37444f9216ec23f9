// --set that changes a section's type (#54 item 1): the section is replaced
// whole, as `extends` replaces it -- the old type's keys dropped, the new
// type's defaults, then the other --set keys of the section over it, in
// whatever order the options came; a key of another type is refused naming
// the type; the resolved scenario holds the new section only.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "config/scenario.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::config {
namespace {

using testing::errorOf;
using testing::kRigid;
using testing::readFile;

// The keys of a section of the resolved scenario (config.resolved.yaml's text).
std::set<std::string> resolvedKeys(const Scenario& s, const std::string& section) {
  std::set<std::string> keys;
  for (const auto& entry : YAML::Load(toYaml(s))[section]) keys.insert(entry.first.Scalar());
  return keys;
}

const std::vector<std::string> kBaseline = {"controller.type=pd_plus_differenced", "controller.kp=[150, 10]",
                                            "controller.kd=[15, 1]"};

TEST(SetType, AControllerOfAnotherTypeReplacesTheSection) {
  const Scenario s = loadScenario(kRigid, kBaseline);
  EXPECT_EQ(s.controller.type, "pd_plus_differenced");
  EXPECT_EQ(s.controller.params.at("kp"), Eigen::Vector2d(150, 10));
  EXPECT_EQ(s.controller.params.at("kd"), Eigen::Vector2d(15, 1));
  // theorem1's a, b and initial_filter_state are gone, not refused.
  EXPECT_EQ(resolvedKeys(s, "controller"), (std::set<std::string>{"type", "kp", "kd"})) << toYaml(s);
}

TEST(SetType, TheOrderOfTheOptionsDoesNotMatter) {
  const std::string forward = toYaml(loadScenario(kRigid, kBaseline));
  const std::string reverse = toYaml(loadScenario(
      kRigid, {"controller.kd=[15, 1]", "controller.kp=[150, 10]", "controller.type=pd_plus_differenced"}));
  EXPECT_EQ(forward, reverse);
  // A whole section given as a map with its type is a type change too.
  const std::string as_map = toYaml(loadScenario(
      kRigid, {"controller.kd=[15, 1]", "controller={type: pd_plus_differenced, kp: [150, 10]}"}));
  EXPECT_EQ(forward, as_map);
}

TEST(SetType, TheSameTypeKeepsTheFilesKeys) {
  const Scenario s = loadScenario(kRigid, {"controller.type=theorem1", "controller.kp=[100, 8]"});
  EXPECT_EQ(resolvedKeys(s, "controller"), resolvedKeys(loadScenario(kRigid), "controller"));
}

TEST(SetType, AKeyOfAnotherTypeIsRefusedNamingTheType) {
  std::vector<std::string> overrides = kBaseline;
  overrides.push_back("controller.a=[50, 50]");
  const std::string error = errorOf(readFile(kRigid), overrides);
  EXPECT_NE(
      error.find("controller.a: unknown key (from --set controller.a=[50, 50]); expected one of: kd, kp, "
                 "type (the keys of controller type pd_plus_differenced)"),
      std::string::npos)
      << error;
}

TEST(SetType, AMissingKeyOfTheNewTypeSaysTheSectionWasReplaced) {
  const std::string error = errorOf(readFile(kRigid), {"controller.type=pd_plus_differenced"});
  EXPECT_NE(error.find("controller.kp: missing"), std::string::npos) << error;
  EXPECT_NE(error.find("(--set controller.type=pd_plus_differenced replaced the section controller whole"),
            std::string::npos)
      << error;
}

TEST(SetType, AReferenceOfAnotherTypeDropsTheOldTypesKeys) {
  // rigid_2dof's smooth_sine has alpha, which a sine refuses: it is dropped.
  const Scenario s = loadScenario(kRigid, {"reference.type=sine", "reference.offset=[0.5, 1]",
                                           "reference.amplitude=0.2", "reference.frequency=3"});
  EXPECT_EQ(s.reference.type, model::ReferenceType::kSine);
  EXPECT_EQ(s.reference.offset, Eigen::Vector2d(0.5, 1));
  EXPECT_EQ(resolvedKeys(s, "reference").count("alpha"), 0u) << toYaml(s);
  // Its keys are the new type's to give: the file's offset is gone too.
  const std::string error = errorOf(readFile(kRigid), {"reference.type=sine"});
  EXPECT_NE(error.find("reference.offset: missing"), std::string::npos) << error;
  EXPECT_NE(error.find("replaced the section reference whole"), std::string::npos) << error;
}

TEST(SetType, AnExternalPlantReplacesTheSimulatedPlantsSection) {
  // The file's physics_step is the simulated plant's, refused beside an
  // external one: dropped with the section.
  const Scenario s = loadScenario(kRigid, {"plant.command=[true]", "plant.type=external"});
  EXPECT_TRUE(s.plant.external());
  EXPECT_EQ(resolvedKeys(s, "plant").count("physics_step"), 0u) << toYaml(s);
}

// The rule is extends' rule: the same section from a file extending the
// scenario and from --set resolve alike.
TEST(SetType, ExtendsAndSetResolveAlike) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "lagrange-set-type-extends";
  std::filesystem::create_directories(dir);
  const std::string child = (dir / "child.yaml").string();
  std::ofstream(child) << "extends: " << kRigid
                       << "\ncontroller: {type: pd_plus_differenced, kp: [150, 10], kd: [15, 1]}\n";
  Scenario extended = loadScenario(child);
  std::filesystem::remove_all(dir);
  EXPECT_EQ(toYaml(extended), toYaml(loadScenario(kRigid, kBaseline)));
}

}  // namespace
}  // namespace lagrange::config
