// The front end's seam (tools/front_end.hpp, tools/subcommand.hpp): a
// subcommand is its own files plus one entry in the list the front end is
// given -- shown here by a test-only command beside real ones -- and the
// front end turns every command line CLI11 refuses into bad input (exit 2).
#include "tools/front_end.hpp"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/configs.hpp"
#include "tools/check_gains/check_gains.hpp"
#include "tools/run/run_command.hpp"
#include "util/error.hpp"

namespace lagrange::tools {
namespace {

struct GreetSeen {
  std::string word;
  int runs = 0;
  Invocation invocation;
};
GreetSeen greet_seen;

// A subcommand that exists only in this test: its options, bound to state
// its runner owns, and what it returns.
Subcommand addGreetCommand(CLI::App& app) {
  auto word = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("greet", "test-only: remember a word");
  cmd->add_option("word", *word, "the word")->required();
  return {cmd, [word](const Invocation& inv) {
            greet_seen.word = *word;
            greet_seen.runs += 1;
            greet_seen.invocation = inv;
            return 7;
          }};
}

// A test-only command that throws what its argument names, past its own code.
Subcommand addThrowCommand(CLI::App& app) {
  auto what = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("throw", "test-only: throw");
  cmd->add_option("what", *what, "bad-input, fault or other")->required();
  return {cmd, [what](const Invocation&) -> int {
            if (*what == "bad-input") throw BadInput("the file is wrong");
            if (*what == "fault") throw RuntimeFault("the disk is full");
            throw std::invalid_argument("a broken precondition");
          }};
}

int dispatchArgs(std::vector<std::string> args, const std::vector<AddSubcommand>& commands) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  return dispatch(static_cast<int>(args.size()), argv.data(), commands);
}

TEST(FrontEnd, ATestOnlySubcommandBesideRealOnesRunsWithItsOptions) {
  greet_seen = {};
  EXPECT_EQ(
      dispatchArgs({"lagrange", "greet", "hello"}, {addRunCommand, addGreetCommand, addCheckGainsCommand}),
      7);
  EXPECT_EQ(greet_seen.runs, 1);
  EXPECT_EQ(greet_seen.word, "hello");
  ASSERT_EQ(greet_seen.invocation.argv.size(), 3u);
  EXPECT_EQ(greet_seen.invocation.argv[0], greet_seen.invocation.self_exe);  // absolute, to re-execute
  EXPECT_EQ(greet_seen.invocation.argv[2], "hello");
  EXPECT_TRUE(greet_seen.invocation.sign);
}

TEST(FrontEnd, EveryRefusedCommandLineIsBadInputAndRunsNothing) {
  greet_seen = {};
  const std::vector<AddSubcommand> commands = {addGreetCommand, addCheckGainsCommand};
  EXPECT_EQ(dispatchArgs({"lagrange"}, commands), kExitBadInput);           // no subcommand
  EXPECT_EQ(dispatchArgs({"lagrange", "nope"}, commands), kExitBadInput);   // unknown one
  EXPECT_EQ(dispatchArgs({"lagrange", "greet"}, commands), kExitBadInput);  // its argument missing
  EXPECT_EQ(dispatchArgs({"lagrange", "greet", "a", "--x"}, commands), kExitBadInput);  // an unknown option
  EXPECT_EQ(greet_seen.runs, 0);
  EXPECT_EQ(dispatchArgs({"lagrange", "--help"}, commands), kExitOk);
  EXPECT_EQ(dispatchArgs({"lagrange", "greet", "--help"}, commands), kExitOk);
  EXPECT_EQ(greet_seen.runs, 0);
}

// --version after a command prints the version as before it does, though
// the command's required argument is missing, and runs nothing.
TEST(FrontEnd, EveryCommandTakesVersion) {
  greet_seen = {};
  const std::vector<AddSubcommand> commands = {addGreetCommand, addRunCommand};
  const auto printed = [&](std::vector<std::string> args, int* status) {
    std::ostringstream captured;
    std::streambuf* const old = std::cout.rdbuf(captured.rdbuf());
    *status = dispatchArgs(std::move(args), commands);
    std::cout.rdbuf(old);
    return captured.str();
  };
  int status = -1;
  const std::string version = printed({"lagrange", "--version"}, &status);
  EXPECT_EQ(status, kExitOk);
  EXPECT_EQ(version.rfind("lagrange ", 0), 0u) << version;
  for (const char* command : {"greet", "run"}) {
    EXPECT_EQ(printed({"lagrange", command, "--version"}, &status), version) << command;
    EXPECT_EQ(status, kExitOk) << command;
  }
  EXPECT_EQ(greet_seen.runs, 0);
}

TEST(FrontEnd, WhatACommandLetsEscapeIsNamedAndExitsByItsKindNotAsACrash) {
  std::ostringstream captured;
  std::streambuf* const old = std::cerr.rdbuf(captured.rdbuf());
  const int bad = dispatchArgs({"lagrange", "throw", "bad-input"}, {addThrowCommand});
  const int fault = dispatchArgs({"lagrange", "throw", "fault"}, {addThrowCommand});
  const int other = dispatchArgs({"lagrange", "throw", "other"}, {addThrowCommand});
  std::cerr.rdbuf(old);
  EXPECT_EQ(bad, kExitBadInput);
  EXPECT_EQ(fault, kExitFailed);
  EXPECT_EQ(other, kExitFailed);
  EXPECT_EQ(captured.str(),
            "lagrange throw: the file is wrong\n"
            "lagrange throw: the disk is full\n"
            "lagrange throw: a broken precondition\n");
}

TEST(FrontEnd, ARealCommandGetsItsOwnOptionsThroughTheDispatch) {
  const std::string config = testing::kRigid;
  EXPECT_EQ(dispatchArgs({"lagrange", "check-gains", config}, {addGreetCommand, addCheckGainsCommand}),
            kExitOk);
  // --set reaches the scenario: a gain eq. (12) refuses, then a key no reader knows.
  EXPECT_EQ(dispatchArgs({"lagrange", "check-gains", config, "--set", "controller.kp=[0.001, 0.001]"},
                         {addCheckGainsCommand}),
            kExitFailed);
  EXPECT_EQ(dispatchArgs({"lagrange", "check-gains", config, "--set", "controller.no_such_key=1"},
                         {addCheckGainsCommand}),
            kExitBadInput);
}

}  // namespace
}  // namespace lagrange::tools

namespace lagrange::tools {
namespace {

// `lagrange run`'s scenario is required (its absence is named), though
// optional to the parser (a bare --check may take it first): the usage line
// shows it so, without brackets (#54).
TEST(FrontEnd, RunsUsageShowsTheScenarioAsRequired) {
  CLI::App app{"test", "lagrange"};
  const Subcommand run = addRunCommand(app);
  const std::string help = run.cli->help();
  EXPECT_NE(help.find("run [OPTIONS] SCENARIO\n"), std::string::npos) << help;
  EXPECT_EQ(help.find("[SCENARIO]"), std::string::npos) << help;
}

}  // namespace
}  // namespace lagrange::tools
