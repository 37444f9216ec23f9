// The front door's help: `lagrange --help` is one line per command within 80
// columns; each `lagrange COMMAND --help` starts with that line and ends with
// examples, and every example works as typed from the repository's root (run
// here in a folder that has its configs/, sweeps/ and examples/). The spy's
// example needs a display and a live run: spy_test.cpp runs it.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <sstream>

#include "support/help_examples.hpp"
#include "support/launch.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// The commands `lagrange --help` lists, with their one-line summaries.
std::vector<std::pair<std::string, std::string>> listedCommands(const std::string& help) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream lines(help);
  bool in_list = false;
  for (std::string line; std::getline(lines, line);) {
    if (line == "Subcommands:") {
      in_list = true;
      continue;
    }
    if (!in_list) continue;
    if (line.empty()) break;  // the list's end
    std::istringstream words(line);
    std::string name;
    words >> name;
    std::string summary;
    std::getline(words, summary);
    out.emplace_back(name, summary.substr(summary.find_first_not_of(' ')));
  }
  return out;
}

// Columns of UTF-8 text (a character each).
size_t columns(const std::string& line) {
  size_t n = 0;
  for (const char c : line) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

TEST(Help, TheFrontEndListsOneLinePerCommandWithin80Columns) {
  const RunResult r = lagrange("--help");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) EXPECT_LE(columns(line), 80u) << line;
  const auto listed = listedCommands(r.output);
  std::set<std::string> names;
  for (const auto& [name, summary] : listed) names.insert(name);
  EXPECT_EQ(names, (std::set<std::string>{"run", "check-gains", "replay", "report", "export", "compare",
                                          "sweep", "tune", "keygen", "keys", "spy", "view"}))
      << r.output;
}

TEST(Help, EveryCommandStartsWithItsSummaryAndItsExamplesRun) {
  const std::string work = freshDir("help-examples");
  fs::create_directories(work + "/runs");
  for (const char* folder : {"configs", "sweeps", "examples", "robots"})
    fs::create_directory_symlink(std::string(LAGRANGE_SOURCE_DIR) + "/" + folder, work + "/" + folder);
  int examples_run = 0;
  for (const auto& [name, summary] : listedCommands(lagrange("--help").output)) {
    const CommandHelp help = commandHelp(name);
    EXPECT_EQ(help.summary, summary) << name << ": --help must start with the line `lagrange --help` lists";
    EXPECT_TRUE(help.ends_with_examples) << name << "'s --help does not end with its examples:\n"
                                         << help.text;
    ASSERT_FALSE(help.examples.empty()) << name << "'s --help has no example:\n" << help.text;
    for (const std::string& example : help.examples) {
      EXPECT_EQ(example.rfind("lagrange " + name + " ", 0), 0u) << example;
      if (name == "spy") continue;  // a window on a live run: spy_test.cpp runs it under Xvfb
      // The viewer serves until stopped: it has worked when it serves the page.
      const std::string typed = name == "view" ? "timeout 5 " + example : example;
      const RunResult r = runExample(typed, work);
      if (name == "view") {
        EXPECT_EQ(r.exit_code, 124) << example << "\n" << r.output;
        EXPECT_NE(r.output.find("at http://127.0.0.1:8642/"), std::string::npos) << r.output;
      } else {
        EXPECT_EQ(r.exit_code, 0) << example << "\n" << r.output;
      }
      ++examples_run;
    }
  }
  // A command's own subcommand: `sweep collect` merges the sweep the examples above wrote.
  const CommandHelp collect = commandHelp("sweep collect");
  EXPECT_LE(columns(collect.summary), 80u) << collect.summary;
  EXPECT_TRUE(collect.ends_with_examples) << collect.text;
  ASSERT_EQ(collect.examples.size(), 1u) << collect.text;
  const RunResult merged = runExample(collect.examples[0], work);
  EXPECT_EQ(merged.exit_code, 0) << collect.examples[0] << "\n" << merged.output;
  EXPECT_GE(examples_run, 14);
  fs::remove_all(work);
}

// The processes' --help: what they are, how they are started, an example.
TEST(Help, EveryProcessStartsWithWhatItIsAndEndsWithAnExample) {
  for (const char* process : {"plant", "controller", "actuator", "logger"}) {
    const RunResult r = shell(kBin + "/lagrange-" + std::string(process) + " --help");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string first = r.output.substr(0, r.output.find('\n'));
    EXPECT_LE(columns(first), 80u) << first;
    EXPECT_EQ(first.find("Usage"), std::string::npos) << "no summary first: " << first;
    const size_t examples = r.output.rfind("\nExamples:\n  lagrange-" + std::string(process) + " --config ");
    EXPECT_NE(examples, std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace lagrange::testing
