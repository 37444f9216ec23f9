// lagrange report draws the plots of every kind of run -- rigid, actuator
// chain, flexible joints, realtime (timing histograms) -- as real PNG files,
// titled by the scenario; `lagrange run --report` does the same at the end of
// a run; a log without its scenario still gets its plots, with a warning.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <set>
#include <sstream>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/sweep_files.hpp"
#include "util/number_text.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// Width and height of a PNG file (its IHDR chunk), or {0, 0} if it is not a PNG.
std::pair<uint32_t, uint32_t> pngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char head[24] = {};
  in.read(reinterpret_cast<char*>(head), sizeof head);
  const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(magic, magic + 8, head) ||
      std::string(reinterpret_cast<char*>(head + 12), 4) != "IHDR")
    return {0, 0};
  const auto be32 = [&](int at) {
    return uint32_t(head[at]) << 24 | uint32_t(head[at + 1]) << 16 | uint32_t(head[at + 2]) << 8 |
           head[at + 3];
  };
  return {be32(16), be32(20)};
}

std::set<std::string> pngsIn(const std::string& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".png") out.insert(e.path().filename().string());
  return out;
}

void expectPlots(const std::string& dir, const std::set<std::string>& expected, const std::string& context) {
  EXPECT_EQ(pngsIn(dir), expected) << context;
  for (const auto& png : expected) {
    const auto [width, height] = pngSize(dir + "/" + png);
    EXPECT_EQ(width, 1100u) << png << " is not a 1100 px wide PNG (" << context << ")";
    EXPECT_GE(height, 600u) << png;
  }
}

// What any log's CSV files allow; a log with its scenario adds the per-joint
// errors (TRACKING.csv: the truth against the scenario's reference).
const std::set<std::string> kEveryLog = {"tracking_error.png", "joints.png", "velocities.png", "torques.png",
                                         "filter_states.png"};

std::set<std::string> with(std::set<std::string> base, const std::set<std::string>& more) {
  base.insert(more.begin(), more.end());
  return base;
}

const std::set<std::string> kEveryRun = with(kEveryLog, {"joint_errors.png"});

TEST(Report, EveryKindOfRunGetsItsPlotsTitledByItsScenario) {
  const std::set<std::string> chain = {"chain_error.png", "control_input.png", "actuator_states.png"};
  const std::vector<std::tuple<std::string, std::set<std::string>, std::string>> cases = {
      {"rigid_2dof_lockstep", kEveryRun, "rigid_2dof (lockstep, theorem1)"},
      {"chain_m2_lockstep", with(kEveryRun, chain), "chain_m2 (lockstep, cascaded)"},
      {"flexible_2dof_filtered_rate_lockstep", with(kEveryRun, {"motors.png"}),
       "flexible_2dof_filtered_rate (lockstep, flexible)"},
      {"chain_m1_realtime", with(with(kEveryRun, chain), {"timing.png"}), "chain_m1 (realtime, cascaded)"},
      {"panda_theorem1_lockstep", kEveryRun, "panda_theorem1 (lockstep, theorem1)"},
  };
  for (const auto& [log, expected, title] : cases) {
    const std::string out = freshDir("report-" + log);
    const RunResult r = lagrange("report " + quote(kGoldenDir + log + ".lcm") + " -o " + quote(out));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    expectPlots(out, expected, log);
    std::ifstream script(out + "/plots.gp");
    const std::string text((std::istreambuf_iterator<char>(script)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("'" + title + ": tracking error norm"), std::string::npos) << log;
  }
}

// A URDF arm's seven joints: one panel per joint, each named by the URDF's
// joint name next to its number, tall enough to read (260 px a panel); the
// torque legend names them too. The planar chain's panels keep numbers alone.
TEST(Report, AUrdfArmsPlotsNameItsJoints) {
  const std::string out = freshDir("report-panda");
  ASSERT_EQ(
      lagrange("report " + quote(kGoldenDir + "panda_theorem1_lockstep.lcm") + " -o " + quote(out)).exit_code,
      0);
  std::ifstream script(out + "/plots.gp");
  const std::string text((std::istreambuf_iterator<char>(script)), std::istreambuf_iterator<char>());
  for (int j = 1; j <= 7; ++j) {
    const std::string n = std::to_string(j);
    EXPECT_NE(text.find("set ylabel 'q" + n + " (panda_joint" + n + ") [rad]'"), std::string::npos) << j;
    EXPECT_NE(text.find("title 'τ" + n + " (panda_joint" + n + ")'"), std::string::npos) << j;
  }
  EXPECT_GE(pngSize(out + "/joints.png").second, 7u * 260u);
  const std::string planar = freshDir("report-planar");
  ASSERT_EQ(
      lagrange("report " + quote(kGoldenDir + "rigid_2dof_lockstep.lcm") + " -o " + quote(planar)).exit_code,
      0);
  std::ifstream planar_script(planar + "/plots.gp");
  const std::string planar_text((std::istreambuf_iterator<char>(planar_script)),
                                std::istreambuf_iterator<char>());
  EXPECT_NE(planar_text.find("set ylabel 'q1 [rad]'"), std::string::npos);
  EXPECT_EQ(planar_text.find("(joint1)"), std::string::npos);
}

TEST(Report, RealtimeTimingTableHasARowPerTick) {
  const std::string out = freshDir("report-timing");
  ASSERT_EQ(lagrange("report " + quote(kGoldenDir + "chain_m1_realtime.lcm") + " -o " + quote(out)).exit_code,
            0);
  std::ifstream timing(out + "/TIMING.csv");
  std::string header, line;
  std::getline(timing, header);
  EXPECT_EQ(header, "tick,period_error_us,command_latency_us,actuator_latency_us");
  long long rows = 0, with_latency = 0;
  while (std::getline(timing, line)) {
    ++rows;
    const auto third = line.find(',', line.find(',') + 1);
    with_latency += line.size() > third + 1 && line[third + 1] != ',';
  }
  EXPECT_EQ(rows, 1001);
  EXPECT_GE(with_latency, 990);  // a command answered nearly every sample
}

TEST(Report, RunWithReportFlagWritesThePlotsAtTheEnd) {
  const std::string out = freshDir("run-report");
  const RunResult r = runScenario(std::string(LAGRANGE_SOURCE_DIR) + "/configs/chain_m1.yaml", out,
                                  "--set duration=1 --report");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("report: 5 CSV files, 9 plots in " + out + "/report"), std::string::npos)
      << r.output;
  expectPlots(out + "/report",
              with(kEveryRun, {"chain_error.png", "control_input.png", "actuator_states.png"}),
              "run --report");
}

// TRACKING.csv is the truth against the reference, row by row: each q − q_d
// equals PLANT_TRUTH's q minus the controller's own q_desired of that tick
// (clean sensors, lockstep: the same instant), and the error plots' marker is
// summary.json's convergence time, to the bit.
TEST(Report, TheTrackingTableAndMarkerAgreeWithTheRunsOwnFigures) {
  const std::string out = freshDir("run-report-tracking");
  const RunResult r = runScenario(std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml", out,
                                  "--set duration=2 --report");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto truth = readTruth(out + "/run.lcm");
  const auto desired =
      readReadings(out + "/run.lcm", "CONTROL_COMMAND", &lagrange::control_command_t::q_desired);
  std::ifstream table(out + "/report/TRACKING.csv");
  std::string line;
  std::getline(table, line);
  EXPECT_EQ(line,
            "tick,sim_time,q_error_norm,q_error[1],q_error[2],qdot_desired[1],qdot_desired[2],"
            "qdot_error[1],qdot_error[2]");
  size_t rows = 0;
  while (std::getline(table, line)) {
    std::vector<double> v;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
    ASSERT_EQ(v.size(), 9u) << line;
    const auto& sample = truth.at(rows);
    ASSERT_EQ(static_cast<long long>(v[0]), sample.tick);
    const auto& qd = desired.at(sample.tick);
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(v[3 + j], sample.q(j) - qd[j], 1e-12) << "tick " << sample.tick << " joint " << j + 1;
      EXPECT_NEAR(v[7 + j], sample.qdot(j) - v[5 + j], 1e-12) << "tick " << sample.tick;
    }
    EXPECT_NEAR(v[2], std::hypot(v[3], v[4]), 1e-15);
    ++rows;
  }
  EXPECT_EQ(rows, truth.size());
  const auto summary = readSummary(out);
  const std::string script = readText(out + "/report/plots.gp");
  ASSERT_TRUE(summary["tracking"]["convergence_time"].is_number()) << summary.dump();
  const std::string t = util::exactText(summary["tracking"]["convergence_time"].get<double>());
  EXPECT_NE(script.find("set arrow from " + t + ", graph 0 to " + t + ", graph 1"), std::string::npos) << t;
  // Its torques start with a spike far above their later swing: clipped, and said so.
  EXPECT_NE(script.find("the start-up peaks above are cut"), std::string::npos);
}

// A stock logger started late misses SCENARIO: the plots come from the CSV columns.
TEST(Report, ALogWithoutItsScenarioStillGetsPlots) {
  const std::string dir = freshDir("report-noscenario");
  fs::create_directories(dir);
  const std::string log = dir + "/no_scenario.lcm";
  {
    lcm::LogFile in(kGoldenDir + "chain_m2_lockstep.lcm", "r"), out(log, "w");
    while (const lcm::LogEvent* ev = in.readNextEvent())
      if (ev->channel != "SCENARIO") out.writeEvent(const_cast<lcm::LogEvent*>(ev));
  }
  const RunResult r = lagrange("report " + quote(log) + " -o " + quote(dir + "/report"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: the log has no SCENARIO channel"), std::string::npos) << r.output;
  expectPlots(dir + "/report",
              with(kEveryLog, {"chain_error.png", "control_input.png", "actuator_states.png"}),
              "no scenario");
  EXPECT_FALSE(fs::exists(dir + "/report/TRACKING.csv")) << "no reference to judge the truth against";
}

}  // namespace
}  // namespace lagrange::testing
