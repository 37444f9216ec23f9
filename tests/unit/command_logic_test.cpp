// The logic of subcommands that have no unit test of their own elsewhere,
// run through the front end as a user's command line would: keygen's key
// file, compare's tables (tools/compare/compare_output.hpp), the key
// reference of `lagrange keys` (tools/keys/key_listing.hpp).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/key_file.hpp"
#include "support/temp_dir.hpp"
#include "tools/compare/compare_output.hpp"
#include "tools/front_end.hpp"
#include "tools/keygen/keygen.hpp"
#include "tools/keys/key_listing.hpp"
#include "tools/keys/keys.hpp"
#include "util/error.hpp"

namespace lagrange::tools {
namespace {

class CommandLogic : public lagrange::testing::TempDirTest {
 protected:
  static int lagrangeCommand(std::vector<std::string> args) {
    args.insert(args.begin(), "lagrange");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    return dispatch(static_cast<int>(args.size()), argv.data(), {addKeygenCommand, addKeysCommand});
  }
  static std::string text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
};

// A key a host reads back, private to its owner; never written over.
TEST_F(CommandLogic, KeygenWritesAPrivateKeyAndNeverOverwritesOne) {
  const std::string path = dir_ + "/run.key";
  ASSERT_EQ(lagrangeCommand({"keygen", path}), kExitOk);
  struct stat st {};
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  const std::string first = text(path);
  EXPECT_NO_THROW(runtime::readKeyFile(path));

  EXPECT_EQ(lagrangeCommand({"keygen", path}), kExitBadInput);
  EXPECT_EQ(text(path), first);  // the key hosts already share stays

  const std::string other = dir_ + "/other.key";
  ASSERT_EQ(lagrangeCommand({"keygen", other}), kExitOk);
  EXPECT_NE(text(other), first);  // fresh each time
  EXPECT_EQ(lagrangeCommand({"keygen", dir_ + "/no/such/dir/run.key"}), kExitBadInput);
}

// compare's tables: nominal rows, then the sweep's under its key; a run that
// never converged and numbers a failed run lacks are said, not invented.
TEST_F(CommandLogic, CompareTablesSayWhatEachRunGave) {
  ComparisonTables t;
  t.scenario = "rigid_2dof";
  t.dof = 2;
  t.sweep_key = "controller.kp";
  RunNumbers theorem1;
  theorem1.type = "theorem1";
  theorem1.status = "completed";
  theorem1.convergence_time = 1.25;
  theorem1.final_error = 0.125;  // binary fractions: the CSV prints 17 digits
  theorem1.rms_last_second = 0.0625;
  theorem1.max_torque = 80.0;
  theorem1.total_variation = 120.0;
  theorem1.energy = 3000.0;
  theorem1.verdict = "met";
  RunNumbers never = theorem1;
  never.type = "set_point";
  never.convergence_time.reset();
  never.verdict = "NOT met";
  never.verdict_reason = "a \"quoted\" | piped reason";
  RunNumbers failed;
  failed.type = "theorem1";
  failed.value = "[100, 8]";
  failed.status = "failed (exit 1)";
  t.runs = {theorem1, never, failed};

  const std::string md = writeComparison(t, dir_);
  EXPECT_EQ(md, text(dir_ + "/comparison.md"));
  EXPECT_NE(md.find("# Comparison: rigid_2dof"), std::string::npos);
  EXPECT_NE(md.find("| theorem1 | completed | met | 1.25 | 0.125 | 0.0625 | 80 | 120 | 3e+03 |"),
            std::string::npos)
      << md;
  // The verdict's reason in its cell: a '|' would split the table.
  EXPECT_NE(
      md.find("| set_point | completed | NOT met: a \"quoted\" \\| piped reason | not within the run |"),
      std::string::npos)
      << md;
  const size_t sweep = md.find("## Sweep of controller.kp");
  ASSERT_NE(sweep, std::string::npos) << md;
  EXPECT_GT(md.find("| theorem1 | [100, 8] | failed (exit 1) | — | not within the run |  |  |  |  |  |"),
            sweep)
      << md;

  const std::string csv = text(dir_ + "/comparison.csv");
  std::vector<std::string> lines;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u) << csv;
  EXPECT_EQ(lines[0].rfind("controller,sweep_key,sweep_value,status,convergence_time,", 0), 0u);
  EXPECT_EQ(lines[1], "theorem1,,\"\",completed,1.25,0.125,0.0625,80,120,3000,met,\"\"") << csv;
  EXPECT_EQ(lines[2].substr(lines[2].find(",NOT met,")), ",NOT met,\"a \"\"quoted\"\" | piped reason\"")
      << csv;
  EXPECT_EQ(lines[3], "theorem1,controller.kp,\"[100, 8]\",failed (exit 1),,,,,,,,\"\"") << csv;
}

TEST(KeyListing, ListsASectionsKeysWithTypeDefaultAndRange) {
  const std::string plant = keyListing({"plant"});
  EXPECT_NE(plant.find("plant.physics_step  (number > 0; default `1.0e-4`)\n"), std::string::npos) << plant;
  EXPECT_NE(plant.find("Range: from 1e-7 to 1 s"), std::string::npos) << plant;
  EXPECT_EQ(plant.find("actuator."), std::string::npos) << "only the section asked for:\n" << plant;
  // A row describing its items states their ranges; every line fits the width
  // in columns (characters, not UTF-8 bytes: "≥" and "²" are one column each),
  // and is as full as it can be: the next line's first word would not fit.
  const auto columns = [](const std::string& text) {
    size_t n = 0;
    for (const char c : text) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    return n;
  };
  for (const int width : {40, 50, 60, 72}) {
    const std::string links = keyListing({"robot.links"}, width);
    std::istringstream all_words(links);
    std::string words;
    for (std::string word; all_words >> word;) words += word + " ";
    EXPECT_NE(words.find("`mass` from 1e-6 to 1e6"), std::string::npos) << links;
    EXPECT_NE(links.find("≥"), std::string::npos) << links;
    std::vector<std::string> text;
    std::istringstream lines(links);
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("    ", 0) == 0) text.push_back(line);
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i].find(' ', 4) != std::string::npos) {  // a word longer than the width keeps its own line
        EXPECT_LE(columns(text[i]), static_cast<size_t>(width)) << text[i];
      }
      if (i + 1 < text.size()) {
        const std::string next_word = text[i + 1].substr(4, text[i + 1].find(' ', 4) - 4);
        EXPECT_GT(columns(text[i]) + 1 + columns(next_word), static_cast<size_t>(width))
            << "width " << width << ": '" << next_word << "' fits on\n"
            << text[i];
      }
    }
  }
  // A section ends at a dot or a bracket: "controller.k" is no prefix of controller.kp.
  const std::string stages = keyListing({"controller.stages"});
  EXPECT_NE(stages.find("controller.stages[i].initial_zeta"), std::string::npos);
  EXPECT_EQ(stages.find("controller.kp "), std::string::npos);
  EXPECT_THROW(keyListing({"controller.k"}), BadInput);
  // A key described in another key's row gives that row.
  const std::string mass = keyListing({"robot.links[i].mass"});
  EXPECT_EQ(mass.rfind("robot.links  (list of maps", 0), 0u) << mass;
}

TEST_F(CommandLogic, KeysRefusesASectionNoKeyIsIn) {  // through the front end: exit 2
  try {
    keyListing({"plant", "plants"});
    FAIL() << "a section without keys was accepted";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("'plants'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("controller"), std::string::npos)
        << "the sections are listed: " << e.what();
  }
  EXPECT_EQ(lagrangeCommand({"keys", "nonsense"}), 2);
  EXPECT_EQ(lagrangeCommand({"keys", "--markdown", "plant"}), 2);
  EXPECT_EQ(lagrangeCommand({"keys", "metrics"}), 0);
}

}  // namespace
}  // namespace lagrange::tools
