// `lagrange replay` of logs that lie (#44): a log whose SCENARIO names an
// external controller once made replay run that command, as the user
// replaying it. Now nothing read from a log starts a program: the log's
// command is shown (quoted, its control bytes escaped), the actuator and the
// plant are replayed instead, and only a command the user names after --
// runs -- with its scratch files private. The damaged logs of
// tests/unit/replay_trust_test.cpp end in exit 2 here, never a signal or "DIVERGED".
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/scenario_t.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/log_events.hpp"
#include "support/sweep_files.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// The rigid golden log with its SCENARIO saying that its controller was the
// external program `command`: what a log from anywhere can say.
std::string withExternalController(const std::string& dir, const std::vector<std::string>& command) {
  std::vector<LoggedEvent> events = readEvents(kGoldenRigidLockstep);
  EXPECT_EQ(events.front().channel, "SCENARIO");
  lagrange::scenario_t scenario;
  EXPECT_GT(scenario.decode(events.front().data.data(), 0, static_cast<int>(events.front().data.size())), 0);
  YAML::Node yaml = YAML::Load(scenario.yaml);
  YAML::Node controller;
  controller["type"] = "external";
  for (const std::string& word : command) controller["command"].push_back(word);
  controller["working_directory"] = dir;
  yaml["controller"] = controller;
  YAML::Emitter out;
  out << yaml;
  scenario.yaml = out.c_str();
  events.front().data.assign(static_cast<size_t>(scenario.getEncodedSize()), '\0');
  scenario.encode(events.front().data.data(), 0, static_cast<int>(events.front().data.size()));
  const std::string log = dir + "/external.lcm";
  writeEvents(log, events);
  return log;
}

int modeOf(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(lstat(path.c_str(), &st), 0) << path;
  return static_cast<int>(st.st_mode & 07777);
}

class ExternalReplay : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = freshDir("external-replay");
    fs::create_directories(dir_);
    marker_ = dir_ + "/the-log-ran-this";
    // A terminal escape sequence (set the window title) rides along as the last word.
    log_ = withExternalController(dir_, {"sh", "-c", "touch '" + marker_ + "'", "\x1b]0;owned\x07"});
  }
  std::string dir_, marker_, log_;
};

// #44 finding 2: by default, the controller is not replayed and nothing runs;
// the log's command is shown exactly, and the other components are replayed.
TEST_F(ExternalReplay, ALogsCommandIsShownNeverRun) {
  const RunResult r = lagrange("replay " + quote(log_));
  EXPECT_FALSE(fs::exists(marker_)) << "the log's command ran:\n" << r.output;
  // Not 0: the controller, which a CI job may guard this way, was not replayed.
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("exit 2: the controller was not replayed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("controller NOT replayed: the log's controller is external, and replay runs no "
                          "program a log names"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("    'sh' '-c' 'touch '\\''" + marker_ + "'\\''' $'\\x1b]0;owned\\x07'\n"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << "a control byte of the log reached the terminal";
  EXPECT_NE(r.output.find("name the program yourself after --: lagrange replay"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("actuator reproduced all 1001 recorded outputs bit for bit"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("plant reproduced all 1001 recorded outputs bit for bit"), std::string::npos)
      << r.output;

  // Asked for the controller by name: refused as bad input, still nothing run.
  const RunResult controller = lagrange("replay " + quote(log_) + " --component controller");
  EXPECT_FALSE(fs::exists(marker_)) << "the log's command ran:\n" << controller.output;
  EXPECT_EQ(controller.exit_code, 2) << controller.output;
  EXPECT_NE(controller.output.find("controller NOT replayed"), std::string::npos) << controller.output;
}

// With a command after --, that one runs (here one that exits at once, as a
// controller that fails), never the log's; its output lands in a private
// directory (0700, the file 0600) that the error names, the key is gone,
// and nothing else is left in the temporary directory.
TEST_F(ExternalReplay, OnlyTheCommandTheUserNamesRunsAndItsScratchIsPrivate) {
  const std::string tmp = dir_ + "/tmp", mine = dir_ + "/the-user-ran-this";
  fs::create_directories(tmp);
  const RunResult r = shell("TMPDIR=" + quote(tmp) + " " + kBin + "/lagrange replay " + quote(log_) +
                            " -- sh -c " + quote("touch \"$0\"; echo answering; exit 3") + " " + quote(mine));
  EXPECT_FALSE(fs::exists(marker_)) << "the log's command ran:\n" << r.output;
  EXPECT_TRUE(fs::exists(mine)) << "the user's command did not run:\n" << r.output;
  EXPECT_EQ(r.exit_code, 1) << r.output;  // the program failed: a runtime fault
  EXPECT_NE(
      r.output.find("the external controller exited with code 3 after 0 of 1001 commands (its output: " +
                    tmp + "/lagrange-replay-"),
      std::string::npos)
      << r.output;
  const std::vector<fs::path> left{fs::directory_iterator(tmp), fs::directory_iterator{}};
  ASSERT_EQ(left.size(), 1u) << r.output;
  EXPECT_EQ(modeOf(left[0].string()), 0700);
  const std::vector<fs::path> inside{fs::directory_iterator(left[0]), fs::directory_iterator{}};
  ASSERT_EQ(inside.size(), 1u) << "the key is left behind";
  EXPECT_EQ(inside[0].filename(), "controller.log");
  EXPECT_EQ(modeOf(inside[0].string()), 0600);
  EXPECT_EQ(readText(inside[0].string()), "answering\n");
}

// A command after -- is for an external controller only; without the --, extra words are refused.
TEST_F(ExternalReplay, ACommandIsRefusedWhereNoExternalControllerIsReplayed) {
  const std::string mine = dir_ + "/the-user-ran-this";
  const std::string command = " -- sh -c " + quote("touch \"$0\"") + " " + quote(mine);
  for (const std::string& args : {quote(kGoldenRigidLockstep) + command,
                                  quote(log_) + " --component actuator" + command, quote(log_) + " sh"}) {
    const RunResult r = lagrange("replay " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ":\n" << r.output;
    EXPECT_FALSE(fs::exists(mine)) << args << ":\n" << r.output;
    EXPECT_FALSE(fs::exists(marker_)) << args << ":\n" << r.output;
  }
  EXPECT_NE(lagrange("replay " + quote(kGoldenRigidLockstep) + command)
                .output.find("the log's controller is 'theorem1', which replay builds itself"),
            std::string::npos);
  EXPECT_NE(lagrange("replay " + quote(log_) + " sh").output.find("unexpected arguments after the log: 'sh'"),
            std::string::npos);
}

// The command line sees what the library refuses (tests/unit/replay_trust_test.cpp):
// exit 2 with the tick and the counts, not a signal, not "DIVERGED".
TEST(DamagedLogReplay, ExitsTwoNamingTheGapOrTheMisfit) {
  const std::string dir = freshDir("damaged-replay");
  fs::create_directories(dir);
  std::vector<LoggedEvent> events = readEvents(kGoldenRigidLockstep);
  LoggedEvent& e = events[indexOf<lagrange::actuator_state_t>(events, "ACTUATOR_STATE", 100)];
  auto state = decodeAs<lagrange::actuator_state_t>(e);
  state.order = 1;
  state.xi = {{0.25, 0.25}};
  encodeSealed(e, state);
  events.erase(events.begin() +
               static_cast<long>(indexOf<lagrange::control_command_t>(events, "CONTROL_COMMAND", 531)));
  writeEvents(dir + "/damaged.lcm", events);
  const RunResult actuator = lagrange("replay " + quote(dir + "/damaged.lcm") + " --component actuator");
  EXPECT_EQ(actuator.exit_code, 2) << actuator.output;
  EXPECT_NE(actuator.output.find("ACTUATOR_STATE tick 100 (the event at byte "), std::string::npos)
      << actuator.output;
  EXPECT_NE(actuator.output.find("holds 1 chain row (order), expected 0 (actuator.order)"), std::string::npos)
      << actuator.output;
  const RunResult controller = lagrange("replay " + quote(dir + "/damaged.lcm"));
  EXPECT_EQ(controller.exit_code, 2) << controller.output;
  EXPECT_NE(controller.output.find("the log lacks CONTROL_COMMAND tick 531"), std::string::npos)
      << controller.output;
  EXPECT_EQ(controller.output.find("DIVERGED"), std::string::npos) << controller.output;
}

}  // namespace
}  // namespace lagrange::testing
