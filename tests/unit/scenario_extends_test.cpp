// `extends:` (config/scenario_extends.hpp): a scenario built on another, a
// chain, a cycle refused, a base file's relative paths kept relative to it;
// and a --set error names the option, not "(line 1)".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "config/scenario.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::config {
namespace {

namespace fs = std::filesystem;
using testing::kConfigs;

// A fresh folder of scenario files for one test.
class Extends : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("lagrange-extends-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "sub");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream((dir_ / name).string()) << text;
    return (dir_ / name).string();
  }
  std::string errorLoading(const std::string& path, const std::vector<std::string>& overrides = {}) {
    try {
      loadScenario(path, overrides);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(Extends, MergesMapsKeyByKeyReplacesListsAndThenAppliesSet) {
  write("base.yaml",
        "extends: " + kConfigs + "/rigid_2dof.yaml\nduration: 4.0\nplant: {publish_rate: 2000}\n");
  const std::string child = write("sub/child.yaml",
                                  "extends: ../base.yaml\nname: child\ncontroller: {kd: [7, 8]}\n"
                                  "initial_state: {q: [0.1, 0.2]}\n");
  const Scenario base = loadScenario(kConfigs + "/rigid_2dof.yaml");
  const Scenario s = loadScenario(child, {"duration=3.0"});
  EXPECT_EQ(s.name, "child");
  EXPECT_EQ(s.duration, 3.0) << "--set applies after the merge";
  EXPECT_EQ(s.plant.publish_rate, 2000.0) << "from the middle file";
  EXPECT_EQ(s.plant.physics_step, base.plant.physics_step) << "a key the middle file left alone";
  EXPECT_EQ(s.controller.type, base.controller.type) << "the controller map merged, not replaced";
  EXPECT_EQ(s.initial_state.q, Eigen::Vector2d(0.1, 0.2));
  // The resolved scenario is whole and has no extends.
  const std::string resolved = toYaml(s);
  EXPECT_EQ(resolved.find("extends"), std::string::npos);
  EXPECT_EQ(toYaml(parseScenario(resolved, "resolved")), resolved);
}

TEST_F(Extends, ACycleIsRefusedNamingTheChain) {
  write("a.yaml", "extends: b.yaml\nname: a\n");
  write("b.yaml", "extends: a.yaml\nname: b\n");
  const std::string error = errorLoading((dir_ / "a.yaml").string());
  EXPECT_NE(error.find("extends: a cycle: " + (dir_ / "a.yaml").string() + " -> " +
                       (dir_ / "b.yaml").string() + " -> " + (dir_ / "a.yaml").string()),
            std::string::npos)
      << error;
  write("self.yaml", "extends: self.yaml\nname: s\n");
  EXPECT_NE(errorLoading((dir_ / "self.yaml").string()).find("a cycle"), std::string::npos);
}

// Named from the working directory ("lagrange run a.yaml"): a base's folder
// is still known -- a cycle is named a cycle, and a base's external plant
// starts in the base's folder (it was "cannot be resolved here" and
// "cannot make absolute path" before).
TEST_F(Extends, ScenariosNamedFromTheWorkingDirectoryResolveAsAnyOther) {
  write("a.yaml", "extends: b.yaml\nname: a\n");
  write("b.yaml", "extends: a.yaml\nname: b\n");
  write("external.yaml", "extends: " + kConfigs +
                             "/rigid_2dof.yaml\nplant: {type: external, command: [./my_plant, --fast], "
                             "publish_rate: 1000}\nactuator: {order: 0}\n");
  write("mine.yaml", "extends: external.yaml\nname: mine\n");
  write("my_plant", "#!/bin/sh\n");
  fs::permissions(dir_ / "my_plant", fs::perms::owner_all);
  const fs::path was = fs::current_path();
  fs::current_path(dir_);
  const std::string cycle = errorLoading("a.yaml");
  std::string external_error;
  Scenario mine;
  try {
    mine = loadScenario("mine.yaml");
  } catch (const std::exception& e) {
    external_error = e.what();
  }
  fs::current_path(was);
  EXPECT_NE(cycle.find("extends: a cycle: "), std::string::npos) << cycle;
  EXPECT_EQ(external_error, "");
  EXPECT_EQ(mine.plant.command.at(0), (dir_ / "my_plant").string());
  EXPECT_EQ(fs::path(mine.plant.working_directory), dir_);
}

TEST_F(Extends, AMissingOrBadBaseIsNamed) {
  const std::string missing = write("m.yaml", "extends: nowhere.yaml\nname: m\n");
  EXPECT_NE(errorLoading(missing).find("extends: "), std::string::npos) << errorLoading(missing);
  EXPECT_NE(errorLoading(missing).find("nowhere.yaml"), std::string::npos) << errorLoading(missing);
  const std::string list = write("l.yaml", "extends: [a, b]\nname: l\n");
  EXPECT_NE(errorLoading(list).find("extends: expected the path of another scenario file"),
            std::string::npos);
  EXPECT_NE(testing::errorOf("extends: x.yaml\nname: t\n").find("cannot be resolved here"),
            std::string::npos);
}

TEST_F(Extends, ABaseFilesUrdfStaysRelativeToItsOwnFolder) {
  const std::string child =
      write("panda.yaml", "extends: " + kConfigs + "/panda_theorem1.yaml\nname: mine\nduration: 1.0\n");
  const Scenario s = loadScenario(child);
  EXPECT_EQ(s.dof(), 7);
  ASSERT_TRUE(s.urdf.has_value());
  EXPECT_EQ(s.urdf->file, fs::weakly_canonical(kConfigs + "/../robots/panda.urdf").string())
      << "the base file's ../robots/panda.urdf, from the base file's folder";
}

// A merged tree has no line numbers (an error would say "(line 1)"): an
// error names the line of the file that wrote the key -- this one, or one it
// extends -- and, for a key none wrote, the files.
TEST_F(Extends, AnErrorInAMergedScenarioNamesTheLineOfTheFileThatWroteTheKey) {
  const std::string child = write("child.yaml", "extends: " + kConfigs +
                                                    "/rigid_2dof.yaml\nname: c\n"
                                                    "controller: {kd: abc}\n");
  const std::string error = errorLoading(child);
  EXPECT_NE(error.find("controller.kd: expected"), std::string::npos) << error;
  EXPECT_NE(error.find("(line 3)"), std::string::npos) << error;
  EXPECT_EQ(error.find("extends: "), std::string::npos) << error;

  // Written by the base (an unknown key), two files down the chain.
  write("base.yaml",
        "extends: " + kConfigs + "/rigid_2dof.yaml\nname: b\nplant:\n  publish_rate: 500\n  bogus: 1\n");
  const std::string top = write("top.yaml", "extends: base.yaml\nduration: 2\n");
  const std::string unknown = errorLoading(top);
  EXPECT_NE(unknown.find("plant.bogus: unknown key (line 5 of " + (dir_ / "base.yaml").string() +
                         ", which this file extends)"),
            std::string::npos)
      << unknown;
  // The same key written by both: the scenario's own value is the one read.
  const std::string both = write("both.yaml", "extends: base.yaml\n\nplant: {bogus: 2}\n");
  EXPECT_NE(errorLoading(both).find("plant.bogus: unknown key (line 3)"), std::string::npos)
      << errorLoading(both);
  // A key no file wrote (one missing): the files.
  const std::string missing = write("missing.yaml", "extends: base.yaml\nreference: {type: sine}\n");
  const std::string none = errorLoading(missing);
  EXPECT_NE(none.find("(in this file or one it extends: "), std::string::npos) << none;
  EXPECT_NE(none.find("rigid_2dof.yaml)"), std::string::npos) << none;

  const std::string set = errorLoading(child, {"extends=other.yaml"});
  EXPECT_NE(set.find("--set extends: a scenario's base is read before --set applies"), std::string::npos)
      << set;
}

// A section whose type changes is replaced whole (no theorem1 gain is left in
// an external controller's section), and a base's program path stays its own.
TEST_F(Extends, AControllerOfAnotherTypeReplacesTheSectionAndKeepsItsProgramPath) {
  fs::create_directories(dir_ / "base");
  const std::string program = (dir_ / "base" / "prog.sh").string();
  std::ofstream(program) << "#!/bin/sh\n";
  fs::permissions(program, fs::perms::owner_all);
  write("base/external.yaml",
        "extends: " + kConfigs +
            "/rigid_2dof.yaml\nmode: lockstep\ncontroller: {type: external, command: [./prog.sh, "
            "--gain, 2]}\n");
  const Scenario s = loadScenario(write("child.yaml", "extends: base/external.yaml\nname: c\n"));
  EXPECT_EQ(s.controller.type, "external");
  ASSERT_EQ(s.controller.command.size(), 3u);
  EXPECT_EQ(s.controller.command[0], fs::weakly_canonical(program).string());
  // It starts in the base's folder, where its arguments are (the default is
  // the folder of the file that gave the command) ...
  EXPECT_EQ(fs::path(s.controller.working_directory), fs::weakly_canonical(dir_ / "base"));
  // ... and a command the extending file gives, in the extending file's.
  const Scenario own = loadScenario(
      write("own.yaml",
            "extends: base/external.yaml\ncontroller: {type: external, command: [sh, -c, \'exit 0\']}\n"));
  EXPECT_EQ(fs::path(own.controller.working_directory), fs::weakly_canonical(dir_));
}

// Through relative paths, as a user types them: a base's command starts in
// the base's folder, and a folder the base names itself stays the base's
// when the extending file changes only the command.
TEST_F(Extends, ABasesProgramStartsInItsFolderThroughRelativePathsAndKeepsItsOwnFolder) {
  fs::create_directories(dir_ / "base" / "ctrl");
  const std::string head = "extends: " + kConfigs + "/rigid_2dof.yaml\nmode: lockstep\n";
  write("base/ext.yaml", head + "controller: {type: external, command: [sh, -c, 'exit 0']}\n");
  write("base/ext_wd.yaml",
        head + "controller: {type: external, command: [sh, -c, 'exit 0'], working_directory: ctrl}\n");
  write("sub/child.yaml", "extends: ../base/ext.yaml\n");
  write("sub/child_wd.yaml", "extends: ../base/ext_wd.yaml\ncontroller: {command: [sh, -c, 'exit 1']}\n");
  const fs::path was = fs::current_path();
  fs::current_path(dir_);
  const Scenario s = loadScenario("sub/child.yaml");
  const Scenario t = loadScenario("sub/child_wd.yaml");
  fs::current_path(was);
  EXPECT_EQ(fs::path(s.controller.working_directory), fs::weakly_canonical(dir_ / "base"));
  EXPECT_EQ(fs::path(t.controller.working_directory), fs::weakly_canonical(dir_ / "base" / "ctrl"));
  EXPECT_EQ(t.controller.command.back(), "exit 1");
}

// plant.type external over a base whose plant section has no type (the
// simulated plant's): the section is replaced whole -- no physics_step is
// left to refuse -- and the example extended from elsewhere starts its
// program in the example's folder.
TEST_F(Extends, AnExternalPlantReplacesTheSimulatedPlantsSection) {
  const Scenario s = loadScenario(write(
      "external_plant.yaml",
      "extends: " + kConfigs + "/rigid_2dof.yaml\nplant: {type: external, command: [sh, -c, \'exit 0\']}\n"));
  EXPECT_TRUE(s.plant.external());
  EXPECT_EQ(s.plant.publish_rate, 1000.0);
  const std::string example = std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_plant";
  const Scenario e = loadScenario(write("sub/e.yaml", "extends: " + example + "/rigid_2dof_external.yaml\n"));
  ASSERT_TRUE(e.plant.external());
  EXPECT_EQ(fs::path(e.plant.working_directory), fs::weakly_canonical(example));
  EXPECT_EQ(e.plant.command, (std::vector<std::string>{"python3", "two_link_plant.py"}));
}

TEST(SetErrors, NameTheOptionInsteadOfLineOne) {
  const std::string error =
      testing::errorOf(testing::readFile(kConfigs + "/rigid_2dof.yaml"), {"controller.kd=abc"});
  EXPECT_NE(error.find("controller.kd: expected"), std::string::npos) << error;
  EXPECT_NE(error.find("(from --set controller.kd=abc)"), std::string::npos) << error;
  EXPECT_EQ(error.find("(line 1)"), std::string::npos) << error;
  // An error in the file itself keeps its line.
  std::string text = testing::readFile(kConfigs + "/rigid_2dof.yaml");
  text += "bogus_key: 1\n";
  const std::string in_file = testing::errorOf(text, {"controller.kd=5"});
  EXPECT_NE(in_file.find("bogus_key: unknown key (line "), std::string::npos) << in_file;
  EXPECT_EQ(in_file.find("--set"), std::string::npos) << in_file;
}

}  // namespace
}  // namespace lagrange::config
