// The logic of `lagrange spy`, `report` and `replay` that needs no run:
// the endpoint file a run leaves for spy and view (tools/spy/spy.hpp), how
// spy waits for a run to be going in a folder (tools/spy/live_run.hpp), the
// plots report draws from a run's CSV files (tools/report/plots.hpp), and
// replay's bit-for-bit comparison (tools/replay/replay_log.hpp).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/temp_dir.hpp"
#include "tools/replay/replay_log.hpp"
#include "tools/report/plots.hpp"
#include "tools/spy/live_run.hpp"
#include "tools/spy/spy.hpp"
#include "util/error.hpp"
#include "util/number_text.hpp"

namespace lagrange::tools {
namespace {

class SubcommandLogic : public lagrange::testing::TempDirTest {
 protected:
  void writeFile(const std::string& name, const std::string& text) {
    std::ofstream(dir_ + "/" + name) << text;
  }
  static bool has(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  }
};

TEST_F(SubcommandLogic, SpyFindsTheRunItsEndpointFileNames) {
  RunEndpoint written;
  written.lcm_url = "udpm://239.255.76.67:7701?ttl=0";
  written.run_id = 12345;
  written.netns_pid = 4242;  // the launcher takes the namespace from itself
  written.launcher_pid = 4242;
  writeEndpoint(dir_, written);
  const RunEndpoint read = readEndpoint(dir_);
  EXPECT_EQ(read.lcm_url, written.lcm_url);
  EXPECT_EQ(read.run_id, 12345);
  EXPECT_EQ(read.netns_pid, 4242);
  EXPECT_EQ(read.launcher_pid, 4242);

  // A run on the machine's network, written before launcher_pid existed.
  writeFile("lcm.json", R"({"lcm_url": "udpm://239.255.76.67:7667", "netns_pid": null})");
  const RunEndpoint old = readEndpoint(dir_);
  EXPECT_FALSE(old.netns_pid.has_value());
  EXPECT_FALSE(old.launcher_pid.has_value());
  EXPECT_EQ(old.run_id, 0);
}

TEST_F(SubcommandLogic, SpyRefusesAMissingOrForeignEndpointFileNamingIt) {
  try {
    readEndpoint(dir_);
    FAIL() << "a directory without lcm.json was accepted";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find(dir_ + "/lcm.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("inproc runs have no LCM traffic"), std::string::npos) << e.what();
  }
  // Binary junk too: a NUL is no JSON (a std::string, so that it is not the empty string).
  for (const std::string& text :
       {std::string("{not json"), std::string(R"({"url": "udpm://x"})"),
        std::string(R"({"lcm_url": 7, "netns_pid": null})"), std::string("\0\0", 2)}) {
    writeFile("lcm.json", text);
    try {
      readEndpoint(dir_);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const BadInput& e) {
      EXPECT_NE(std::string(e.what()).find("is not what lagrange run writes"), std::string::npos) << e.what();
    }
  }
}

// What a folder holds, as spy's wait sees it; each state not a live run is
// said with what was expected and how to start one.
TEST_F(SubcommandLogic, SpyTellsAMissingFolderAnEmptyOneAndAnEndedRunApart) {
  const std::string missing = dir_ + "/runs/live";
  LiveRunProbe p = probeLiveRun(missing);
  EXPECT_EQ(p.state, LiveRunProbe::State::kMissing);
  EXPECT_EQ(notLiveText(missing, p),
            "the run folder " + missing +
                " does not exist; expected the output folder of a running `lagrange run "
                "SCENARIO --mode realtime --out " +
                missing + "`");
  p = probeLiveRun(dir_);
  EXPECT_EQ(p.state, LiveRunProbe::State::kNoEndpoint);
  EXPECT_NE(notLiveText(dir_, p).find("inproc runs have no LCM traffic"), std::string::npos);
  writeFile("lcm.json", "{not json");
  p = probeLiveRun(dir_);
  EXPECT_EQ(p.state, LiveRunProbe::State::kRefused);
  EXPECT_NE(notLiveText(dir_, p).find("is not what lagrange run writes"), std::string::npos);
  // A launcher that is gone: a child of this test, exited and reaped.
  const pid_t child = fork();
  if (child == 0) _exit(0);
  ASSERT_GT(child, 0);
  waitpid(child, nullptr, 0);
  writeFile("lcm.json", R"({"lcm_url": "udpm://239.255.76.67:7667?ttl=0", "run_id": 1, "netns_pid": null,)"
                        R"( "launcher_pid": )" +
                            std::to_string(child) + "}");
  p = probeLiveRun(dir_);
  EXPECT_EQ(p.state, LiveRunProbe::State::kEnded);
  EXPECT_NE(notLiveText(dir_, p).find("has ended (its launcher, pid " + std::to_string(child)),
            std::string::npos);
  writeFile("file", "");
  EXPECT_EQ(probeLiveRun(dir_ + "/file").state, LiveRunProbe::State::kNotAFolder);
}

// spy started before the run: it says it waits (once) and how to start a
// run, and returns the run's endpoint once the folder holds a going run's
// lcm.json; given up, it names what the folder held and the wait.
TEST_F(SubcommandLogic, SpyWaitsForARunToAppearAndSaysWhatItWaitedFor) {
  const std::string live = dir_ + "/runs/live";
  std::ostringstream said;
  int before = 0;
  std::thread run([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    std::filesystem::create_directories(live);
    // Half written first, as a reader may find it: looked at again, not refused at once.
    std::ofstream(live + "/lcm.json") << R"({"lcm_url": "udpm://239.255.)";
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    std::ofstream(live + "/lcm.json")
        << R"({"lcm_url": "udpm://239.255.76.67:7701?ttl=0", "netns_pid": null})";
  });
  const RunEndpoint endpoint = waitForLiveRun(live, 60, said, [&] { ++before; });
  run.join();
  EXPECT_EQ(endpoint.lcm_url, "udpm://239.255.76.67:7701?ttl=0");
  EXPECT_EQ(before, 1);
  EXPECT_EQ(said.str(), "lagrange spy: waiting for a live run in " + live +
                            " (start one with: lagrange run SCENARIO --mode realtime --out " + live +
                            "); Ctrl-C stops\n");

  const std::string never = dir_ + "/never";
  try {
    waitForLiveRun(never, 0.3, said, [] {});
    FAIL() << "a folder that never appeared was waited for and accepted";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("the run folder " + never + " does not exist; expected"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("(waited 0.3 s: --wait)"), std::string::npos) << e.what();
  }
  // Nothing to wait for: what before_waiting throws ends the wait before it starts.
  EXPECT_THROW(waitForLiveRun(never, 60, said, [] { throw BadInput("no display"); }), BadInput);
}

TEST_F(SubcommandLogic, ReportDrawsOnlyWhatTheCsvFilesHold) {
  writeFile("PLANT_TRUTH.csv", "utime,t,tick,q[1],q[2],qdot[1],qdot[2],tau[1],tau[2]\n1,0,0,0,0,0,0,0,0\n");
  writeFile("CONTROL_COMMAND.csv",
            "utime,t,tick,u[1],u[2],q_desired[1],q_desired[2],q_error[1],q_error[2],theta[1],theta[2],"
            "filter_state[1],filter_state[2]\n");
  PlotSpec spec = specFromCsv(dir_, "rigid \"2dof\"");
  EXPECT_EQ(spec.dof, 2);
  EXPECT_EQ(spec.chain_order, 0);
  EXPECT_FALSE(spec.flexible);
  spec.tolerance = 1e-3;
  spec.joint_names = {"shoulder", "elbow"};
  const PlotScript script = plotScript(spec);
  for (const char* png : {"tracking_error.png", "joints.png", "torques.png", "filter_states.png"})
    EXPECT_TRUE(has(script.pngs, png)) << png;
  for (const char* png : {"chain_error.png", "actuator_states.png", "motors.png", "timing.png"})
    EXPECT_FALSE(has(script.pngs, png)) << png << " drawn without its data";
  ASSERT_EQ(script.sections.size(), script.pngs.size());
  for (const std::string& section : script.sections)
    EXPECT_EQ(section.rfind(kGnuplotPreamble, 0), 0u) << "each picture's script stands alone";
  EXPECT_NE(script.text.find("metrics.tolerance = 0.001"), std::string::npos)
      << "the tolerance line is drawn";
  EXPECT_NE(script.text.find("elbow"), std::string::npos) << "joint names label the panels";
  EXPECT_NE(script.text.find("'rigid \"2dof\": "), std::string::npos) << "a title in single quotes, as it is";

  // A chain's CONTROL_COMMAND has xi_error columns per stage: its stages are drawn.
  writeFile("CONTROL_COMMAND.csv",
            "utime,t,tick,u[1],u[2],q_error[1],q_error[2],xi_error[1][1],xi_error[1][2],xi_error[2][1],"
            "xi_error[2][2]\n");
  writeFile("ACTUATOR_STATE.csv", "utime,t,tick,xi[1][1],xi[1][2],xi[2][1],xi[2][2]\n");
  const PlotSpec chain = specFromCsv(dir_, "chain");
  EXPECT_EQ(chain.chain_order, 2);
  EXPECT_TRUE(has(plotScript(chain).pngs, "chain_error.png"));
}

// A log's scenario and joint names are not ours: a title that would run a
// shell command in a double-quoted gnuplot string (`...`), or end a
// single-quoted one (a quote) or the command (a newline), is drawn as text.
TEST_F(SubcommandLogic, ReportTitlesFromALogRunNothing) {
  const std::string marker = dir_ + "/ran";
  writeFile("PLANT_TRUTH.csv", "tick,sim_time,q[1],qdot[1],tau_applied[1]\n0,0,0,0,1\n1,0.001,0.1,0,2\n");
  PlotSpec spec = specFromCsv(dir_, "x`touch " + marker + "`' ; system('touch " + marker +
                                        "') ; '\nsystem(\"touch " + marker + "\")");
  spec.joint_names = {"j`touch " + marker + "`'"};
  const Plots plots = drawPlots(spec);
  EXPECT_FALSE(std::filesystem::exists(marker)) << "a title ran a command";
  EXPECT_TRUE(plots.failed.empty()) << "gnuplot rejected a picture; see " << plots.log;
  EXPECT_FALSE(plots.written.empty());
}

// A torque history whose t = 0 spike is 60 times its later swing: the plot
// keeps the start-up at full range in one panel and draws the whole run
// clipped to the later range in another, naming the peak it cut. The same
// history without the spike is one plain panel.
TEST_F(SubcommandLogic, ReportClipsAStartUpSpikeAndSaysSo) {
  const auto torques = [&](bool spike) {
    std::string csv = "tick,sim_time,q[1],qdot[1],tau_applied[1]\n";
    for (int k = 0; k <= 1000; ++k) {
      const double t = k * 0.01, tau = (spike && k < 5) ? -300.0 + k : 5.0 * std::sin(t);
      csv += std::to_string(k) + "," + util::exactText(t) + ",0,0," + util::exactText(tau) + "\n";
    }
    writeFile("PLANT_TRUTH.csv", csv);
  };
  torques(true);
  PlotSpec spec = specFromCsv(dir_, "spike");
  EXPECT_EQ(spec.end_time, 10.0) << "the last row's time";
  spec.convergence_time = 2.0;  // the transient ends there (in the first half of the run)
  const auto torquePart = [](const PlotScript& script) {
    for (size_t i = 0; i < script.pngs.size(); ++i)
      if (script.pngs[i] == "torques.png") return script.sections[i];
    return std::string();
  };
  const std::string clipped = torquePart(plotScript(spec));
  EXPECT_NE(clipped.find("set multiplot layout 2,1"), std::string::npos) << clipped;
  EXPECT_NE(clipped.find("peak τ = -300 N m (tau_applied[1]) at t = 0 s"), std::string::npos) << clipped;
  EXPECT_NE(clipped.find("set xrange [0:2]"), std::string::npos) << "the start-up panel ends at convergence";
  // The later range is the samples' over t >= 2 s, with 5 % of its span on each side.
  double lo = 5.0, hi = -5.0;
  for (int k = 200; k <= 1000; ++k)
    lo = std::min(lo, 5.0 * std::sin(k * 0.01)), hi = std::max(hi, 5.0 * std::sin(k * 0.01));
  const double margin = 0.05 * (hi - lo);
  EXPECT_NE(
      clipped.find("set yrange [" + util::exactText(lo - margin) + ":" + util::exactText(hi + margin) + "]"),
      std::string::npos)
      << clipped;
  EXPECT_NE(clipped.find("the start-up peaks above are cut"), std::string::npos);

  torques(false);
  const std::string plain = torquePart(plotScript(specFromCsv(dir_, "no spike")));
  EXPECT_EQ(plain.find("multiplot layout"), std::string::npos) << plain;
  EXPECT_EQ(plain.find("cut"), std::string::npos) << plain;
  EXPECT_EQ(plain.find("set yrange"), std::string::npos) << plain;
}

// The error plots mark summary.json's convergence time (a line where it is,
// a word when there is none) only when TRACKING.csv -- the truth against the
// reference -- is there; the rate plots draw a URDF's limits only for joints
// that have one.
TEST_F(SubcommandLogic, ReportMarksConvergenceAndLimitsOnlyWhereTheyExist) {
  writeFile("PLANT_TRUTH.csv", "tick,sim_time,q[1],q[2],qdot[1],qdot[2],tau_applied[1],tau_applied[2]\n");
  writeFile("CONTROL_COMMAND.csv", "tick,sim_time,u[1],u[2],q_error[1],q_error[2]\n");
  PlotSpec spec = specFromCsv(dir_, "marks");
  spec.tolerance = 1e-3;
  spec.convergence_time = 0.915;
  spec.velocity_limits = {2.5, std::numeric_limits<double>::infinity()};
  PlotScript script = plotScript(spec);
  EXPECT_FALSE(has(script.pngs, "joint_errors.png")) << "per-joint errors need TRACKING.csv";
  EXPECT_EQ(script.text.find("converged at"), std::string::npos) << "no TRACKING.csv, no marker";
  EXPECT_NE(script.text.find("the controller''s view"), std::string::npos)
      << "the norm says whose error it is";
  EXPECT_TRUE(has(script.pngs, "velocities.png"));
  size_t limits = 0;
  for (size_t at = 0; (at = script.text.find("velocity limit ±", at)) != std::string::npos; ++at) ++limits;
  EXPECT_EQ(limits, 1u) << "joint 2 has no limit";
  EXPECT_NE(script.text.find("velocity limit ±2.5 rad/s (URDF)"), std::string::npos);

  writeFile("TRACKING.csv",
            "tick,sim_time,q_error_norm,q_error[1],q_error[2],qdot_desired[1],qdot_desired[2]\n");
  script = plotScript(spec);
  EXPECT_TRUE(has(script.pngs, "joint_errors.png"));
  EXPECT_NE(script.text.find("set arrow from 0.915, graph 0 to 0.915, graph 1"), std::string::npos);
  EXPECT_NE(script.text.find("converged at t = 0.915 s"), std::string::npos);
  EXPECT_NE(script.text.find("PLANT_TRUTH against the reference"), std::string::npos);
  spec.convergence_time.reset();
  script = plotScript(spec);
  EXPECT_EQ(script.text.find("converged at"), std::string::npos);
  EXPECT_NE(script.text.find("not within the tolerance at the end of the run"), std::string::npos);
  spec.velocity_limits.clear();
  EXPECT_EQ(plotScript(spec).text.find("velocity limit"), std::string::npos) << "a planar arm has none";
}

// CSV and table numbers: the shortest text that reads back as the same
// double, bit for bit ("0.1", not "0.10000000000000001").
TEST(NumberText, IsTheShortestTextThatRoundTrips) {
  EXPECT_EQ(util::exactText(0.1), "0.1");
  EXPECT_EQ(util::exactText(1e-3), "0.001");
  EXPECT_EQ(util::exactText(2.0), "2");
  EXPECT_EQ(util::exactText(-1.5e300), "-1.5e+300");
  EXPECT_EQ(util::exactText(std::nextafter(0.1, 1.0)), "0.10000000000000002");
  uint64_t state = 12345;
  for (int i = 0; i < 100000; ++i) {  // random bit patterns: every finite double round-trips
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    double x;
    std::memcpy(&x, &state, sizeof x);
    if (!std::isfinite(x)) continue;
    const double back = std::strtod(util::exactText(x).c_str(), nullptr);
    ASSERT_EQ(std::memcmp(&back, &x, sizeof x), 0) << util::exactText(x);
  }
}

TEST(ReplayCompare, IsBitForBit) {
  using replay_log::compare;
  EXPECT_EQ(compare("u[0]", 0.1, 0.1), "");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(compare("u[0]", nan, nan), "") << "the same NaN replayed is no difference";
  EXPECT_EQ(compare("u[0]", 0.0, -0.0), "u[0]: recorded 0, replayed -0");
  // NaNs that differ only in payload print alike; their bits are shown.
  const std::uint64_t other_nan_bits = 0x7ff8000000000001ull;
  double other_nan = 0.0;
  std::memcpy(&other_nan, &other_nan_bits, sizeof other_nan);
  EXPECT_EQ(compare("u[0]", nan, other_nan),
            "u[0]: recorded nan (bits 0x7ff8000000000000), replayed nan (bits 0x7ff8000000000001)");
  const double next = std::nextafter(0.1, 1.0);
  EXPECT_EQ(compare("theta[1]", 0.1, next), "theta[1]: recorded 0.1, replayed 0.10000000000000002");
  Eigen::VectorXd replayed(2);
  replayed << 1.0, 2.0;
  EXPECT_EQ(compare("u", std::vector<double>{1.0, 2.0}, replayed), "");
  EXPECT_EQ(compare("u", std::vector<double>{1.0, 3.0}, replayed), "u[2]: recorded 3, replayed 2");
  EXPECT_EQ(compare("u", std::vector<double>{1.0}, replayed), "u: recorded 1 values, replayed 2");
  EXPECT_EQ(replay_log::at(42, 0.042), "tick 42 (t = 0.042000 s): ");
}

TEST(ReplayCompare, AMissingInputIsNamedWithTheOutputItFeeds) {
  replay_log::Opened o;
  o.logged_shape.joints = 1;
  lagrange::plant_position_t position{};
  position.header.tick = 2;
  position.num_joints = 1;
  position.q = {0.5};
  o.rec.positions = {{2, position}};
  EXPECT_EQ(replay_log::input(o, o.rec.positions, 2, "PLANT_POSITION", "CONTROL_COMMAND", 2).q[0], 0.5);
  try {
    replay_log::input(o, o.rec.positions, 3, "PLANT_POSITION", "CONTROL_COMMAND", 3);
    FAIL() << "a missing tick was found";
  } catch (const ReplayError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "the log lacks PLANT_POSITION tick 3, an input of CONTROL_COMMAND tick 3; outputs before it were "
        "replayed");
  }
  // A copy of it that failed its checksum is named, with its byte offset.
  o.rec.damage.events.push_back(
      {"PLANT_POSITION", 4321, 3, "fails its checksum (its bytes changed after it was sent)"});
  try {
    replay_log::input(o, o.rec.positions, 3, "PLANT_POSITION", "CONTROL_COMMAND", 3);
    FAIL() << "a missing tick was found";
  } catch (const ReplayError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "the log lacks PLANT_POSITION tick 3, an input of CONTROL_COMMAND tick 3 (the copy of "
        "PLANT_POSITION tick 3 it holds is corrupt: the event at byte 4321 fails its checksum (its bytes "
        "changed after it was sent)); outputs before it were replayed");
  }
}

}  // namespace
}  // namespace lagrange::tools
