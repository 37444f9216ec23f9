// `lagrange compare` (docs/comparison.md): each controller runs the scenario
// as its compare section tunes it -- the same run a user gets from `lagrange
// run` with that controller section -- the table carries each run's own
// numbers, the pictures are drawn, a sweep runs every value, and bad input is
// named before any run starts.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

const std::string kShort = "--set duration=2";

std::vector<std::vector<std::string>> csvRows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (char c : line) {
      if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
        cells.push_back(cell), cell.clear();
      else
        cell += c;
    }
    cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(Compare, RunsEachControllerAsItsSectionTunesItAndTabulatesEachRunsOwnNumbers) {
  const std::string config = kConfigs + "/compare_pelican.yaml";
  const std::string out = freshDir("compare");
  const RunResult r = lagrange("compare " + quote(config) + " -o " + quote(out) + " " + kShort +
                               " --controllers theorem1,pd_plus --jobs 2 "
                               "--sweep 'sensors.position.counts_per_revolution=[4096, 1048576]'");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // pd_plus ran with compare.controllers.pd_plus: the same commands as a
  // plain run with that controller section.
  const std::string direct = freshDir("compare-direct");
  ASSERT_EQ(runScenario(config, direct,
                        "-q --mode inproc " + kShort +
                            " --set 'controller={type: pd_plus, kp: [150.0, 10.0], kd: [15.0, 1.0]}'")
                .exit_code,
            0);
  EXPECT_EQ(readCommands(out + "/runs/pd_plus/run.lcm"), readCommands(direct + "/run.lcm"));

  // Six rows: two nominal runs, and two sweep values for each controller,
  // each row the numbers of its run's summary.json.
  const auto rows = csvRows(out + "/comparison.csv");
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(rows[0][0], "controller");
  std::map<std::string, double> rms;
  for (size_t i = 1; i < rows.size(); ++i) {
    const auto& row = rows[i];
    std::string dir = out + "/runs/" + row[0];
    if (!row[2].empty()) {
      for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_directory() && entry.path().filename().string().find(
                                        row[2] == "4096" ? "_4096" : "_1048576") != std::string::npos)
          dir = entry.path().string();
      const std::string resolved = [&] {
        std::ifstream in(dir + "/config.resolved.yaml");
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
      }();
      EXPECT_NE(resolved.find("counts_per_revolution: [" + row[2] + ", " + row[2] + "]"), std::string::npos)
          << dir;
      rms[row[0] + "@" + row[2]] = std::stod(row[6]);
    }
    const auto j = readSummary(dir);
    EXPECT_EQ(row[3], j["status"].get<std::string>());
    EXPECT_EQ(std::stod(row[5]), j["tracking"]["final_error"].get<double>()) << dir;
    EXPECT_EQ(std::stod(row[6]), j["tracking"]["rms_last_second"].get<double>()) << dir;
    EXPECT_EQ(std::stod(row[7]), j["torque"]["max_abs"].get<double>()) << dir;
    EXPECT_EQ(std::stod(row[8]), j["torque"]["total_variation"].get<double>()) << dir;
    EXPECT_EQ(std::stod(row[9]), j["torque"]["energy"].get<double>()) << dir;
  }
  // The encoder's half-count bias dominates at 2^12 counts (7.7e-4 rad on
  // each joint) and not at 2^20: the sweep changed the sensor.
  for (const std::string type : {"theorem1", "pd_plus"})
    EXPECT_GT(rms[type + "@4096"], 10 * rms[type + "@1048576"]) << type;

  for (const std::string png : {"error.png", "torque.png", "sweep.png"})
    EXPECT_GT(fs::file_size(out + "/" + png), 1000u) << png;
  std::ifstream md(out + "/comparison.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("| pd_plus | completed |"), std::string::npos) << text.str();
  EXPECT_NE(r.output.find("## Sweep of sensors.position.counts_per_revolution"), std::string::npos);
}

// Issue #46: an external row whose program crashes was shown as
// `interrupted`, compare exited 0 and said nothing. Now the row is `failed`,
// compare says which process ended how, and exits 1; the other row stands.
TEST(Compare, AnExternalRowThatCrashesIsAFailedRowWithItsReasonAndExitsOne) {
  const std::string out = freshDir("compare-crash");
  const RunResult r =
      lagrange("compare " + quote(kConfigs + "/rigid_2dof.yaml") + " -o " + quote(out) +
               " --set duration=0.2 --set 'compare={controllers: {theorem1: {}, crash: {type: "
               "external, command: [sh, -c, \"echo about to fail; sleep 1; exit 7\"]}}}'");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("lagrange compare: crash failed: process 'controller' exited with code 7; see "),
            std::string::npos)
      << r.output;
  const auto rows = csvRows(out + "/comparison.csv");
  ASSERT_EQ(rows.size(), 3u) << r.output;
  std::map<std::string, std::string> status;
  for (size_t i = 1; i < rows.size(); ++i) status[rows[i][0]] = rows[i][3];
  EXPECT_EQ(status["crash"], "failed");
  EXPECT_EQ(status["theorem1"], "completed");
  std::map<std::string, std::string> final_error;  // a failed run's numbers are no result: blank
  for (size_t i = 1; i < rows.size(); ++i) final_error[rows[i][0]] = rows[i][5];
  EXPECT_EQ(final_error["crash"], "");
  EXPECT_NE(final_error["theorem1"], "");
  // The run's own summary says it too, with the program's last words.
  const auto j = readSummary(out + "/runs/crash");
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["failure"]["process"], "controller");
  EXPECT_EQ(j["failure"]["how"], "exited with code 7");
  EXPECT_EQ(j["failure"]["last_lines"].back(), "about to fail") << j["failure"].dump();
}

TEST(Compare, BadInputIsNamedBeforeAnyRunStarts) {
  const std::string config = kConfigs + "/compare_pelican.yaml";
  const struct {
    std::string args, message;
  } cases[] = {
      {"--controllers theorem1,pid", "--controllers: unknown controller type 'pid'"},
      {"--controllers set_point", "compare.controllers has no section for 'set_point'"},
      {"--controllers pd_plus,pd_plus", "'pd_plus' is named twice"},
      {"--sweep 'sensors.position.counts_per_revolution'", "--sweep: expected KEY=[V1, V2, ...]"},
      {"--sweep 'sensors.position.counts_per_revolution=4096'", "expected a YAML list of at least one value"},
      {"--sweep 'sensors.position.counts_per_revolution=[4096, -1]'",
       "sensors.position.counts_per_revolution: expected whole numbers >= 0"},
      {"--set 'compare.controllers.slotine_li={kp: 1}'", "compare.controllers.slotine_li"},
      {"--set 'compare.controllers.pid={kp: 1}'", "compare.controllers: unknown controller type 'pid'"},
  };
  for (const auto& c : cases) {
    const std::string out = freshDir("compare-bad");
    const RunResult r = lagrange("compare " + quote(config) + " -o " + quote(out) + " " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
    EXPECT_FALSE(fs::exists(out + "/runs")) << c.args;
  }
}

}  // namespace
}  // namespace lagrange::testing
