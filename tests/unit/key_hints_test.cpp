// Near misses named (#54 item 4): an unknown key that is a case, "_" or small
// spelling neighbour of a known key at the same place says "did you mean
// kd?", before the known key it hides is called missing; keys students guess
// (controller.rate, dt) point to the key that means it. Alike for a YAML
// file and --set (the Python keywords are --set).
#include "config/key_hints.hpp"

#include <gtest/gtest.h>

#include "config/key_ranges.hpp"
#include "config/scenario.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::config {
namespace {

using testing::errorOf;
using testing::kRigid;
using testing::readFile;

// rigid_2dof's text with `from` (its first occurrence) replaced by `to`.
std::string rigidWith(const std::string& from, const std::string& to) {
  std::string text = readFile(kRigid);
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(KeyHints, NearMissesAreCaseUnderscoreAndSmallSpellingNeighbours) {
  const std::set<std::string> gains = {"a", "b", "kd", "kp", "type"};
  EXPECT_EQ(nearMisses("Kd", gains), std::vector<std::string>{"kd"});
  EXPECT_EQ(nearMisses("K_P", gains), std::vector<std::string>{"kp"});
  EXPECT_EQ(nearMisses("A", gains), std::vector<std::string>{"a"});
  EXPECT_TRUE(nearMisses("ki", gains).empty()) << "one letter of two is another word";
  EXPECT_TRUE(nearMisses("tpye", {"kp", "type"}).size() == 1);
  const std::set<std::string> external = {"command", "type", "working_directory"};
  EXPECT_EQ(nearMisses("comand", external), std::vector<std::string>{"command"});
  EXPECT_EQ(nearMisses("working_dir", external), std::vector<std::string>{});
  EXPECT_EQ(nearMisses("physics_stpe", {"physics_step", "publish_rate"}),
            std::vector<std::string>{"physics_step"});
  EXPECT_EQ(unknownKeyHint("kdd", "controller.kdd", {"kd", "kdx", "kdy"}), "; did you mean kdx or kdy?");
}

TEST(KeyHints, AMisspeltRequiredKeyIsNamedBeforeItsKeyIsCalledMissing) {
  const std::string error = errorOf(rigidWith("  kd: [15.0, 1.0]", "  Kd: [15.0, 1.0]"));
  EXPECT_NE(error.find("config: test.yaml: controller.Kd: unknown key (line "), std::string::npos) << error;
  EXPECT_NE(error.find("); did you mean kd? controller.kd is missing"), std::string::npos) << error;
  // A top-level section likewise.
  const std::string section = errorOf(rigidWith("\ncontroller:", "\ncontroler:"));
  EXPECT_NE(section.find("controler: unknown key (line "), std::string::npos) << section;
  EXPECT_NE(section.find("did you mean controller? controller is missing"), std::string::npos) << section;
}

TEST(KeyHints, AnExternalCommandMisspeltIsNamed) {
  const std::string error =
      errorOf(readFile(kRigid), {"controller={type: external, comand: [python3, law.py]}"});
  EXPECT_NE(error.find("controller.comand: unknown key"), std::string::npos) << error;
  EXPECT_NE(error.find("did you mean command? controller.command is missing"), std::string::npos) << error;
}

TEST(KeyHints, AnOptionalKeyMisspeltIsRefusedWithTheSuggestion) {
  const std::string in_file =
      errorOf(rigidWith("  physics_step: 2.5e-5", "  physics_stpe: 2.5e-5\n  physics_step: 2.5e-5"));
  EXPECT_NE(
      in_file.find("plant.physics_stpe: unknown key (line 28); did you mean physics_step? expected one of:"),
      std::string::npos)
      << in_file;
  const std::string by_set = errorOf(readFile(kRigid), {"plant.Publish_Rate=2000"});
  EXPECT_NE(by_set.find("plant.Publish_Rate: unknown key (from --set plant.Publish_Rate=2000); did you mean "
                        "publish_rate?"),
            std::string::npos)
      << by_set;
}

TEST(KeyHints, KeysStudentsGuessPointToTheKeyThatMeansIt) {
  for (const std::string key : {"controller.rate", "controller.frequency", "rate", "plant.rate"}) {
    const std::string error = errorOf(readFile(kRigid), {key + "=200"});
    EXPECT_NE(error.find(key + ": unknown key (from --set " + key +
                         "=200); the control rate is plant.publish_rate [Hz]"),
              std::string::npos)
        << error;
  }
  const std::string period = errorOf(readFile(kRigid), {"controller.period=0.005"});
  EXPECT_NE(
      period.find("controller.period: unknown key (from --set controller.period=0.005); the control period "
                  "is 1 / plant.publish_rate"),
      std::string::npos)
      << period;
  const std::string in_file = errorOf(readFile(kRigid) + "dt: 0.001\n");
  EXPECT_NE(in_file.find("dt: unknown key (line "), std::string::npos) << in_file;
  EXPECT_NE(in_file.find("the simulation's step is plant.physics_step [s]; the control period is 1 / "
                         "plant.publish_rate"),
            std::string::npos)
      << in_file;
}

// A guess that became a key would be refused with a wrong hint; every guess
// is a key the table lacks, and its hint names only keys the table has.
TEST(KeyHints, EveryGuessIsAnUnknownKeyAndPointsToKnownOnes) {
  for (const auto& [guess, meaning] : keyGuesses()) {
    EXPECT_FALSE(isTableKey(guess)) << guess;
    for (const std::string named : {"plant.publish_rate", "plant.physics_step", "duration"})
      if (meaning.find(named) != std::string::npos) {
        EXPECT_TRUE(isTableKey(named)) << named;
      }
  }
  EXPECT_GE(keyGuesses().size(), 6u);
}

}  // namespace
}  // namespace lagrange::config
