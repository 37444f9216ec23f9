// lagrange replay: the controller core fed the recorded inputs reproduces
// every recorded command bit for bit, for lockstep and realtime logs; a
// perturbed gain is caught at the first tick it matters; bad logs are named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <regex>
#include <stdexcept>

#include "support/configs.hpp"
#include "support/launch.hpp"

namespace lagrange::testing {
namespace {

// Short recordings the tests below replay: chain_m2 and
// flexible_2dof_filtered_rate in lockstep, chain_m1 in realtime. Each is made
// the first time a test asks for it: ctest runs every test in a process of
// its own, so a test records only what it replays (and only the test that
// replays the realtime log has to run alone, tests/CMakeLists.txt). A
// recording that fails throws, which fails the test asking for it, naming why.
class Recorded : public ::testing::Test {
 protected:
  static const std::string& recording(const std::string& config, const std::string& extra) {
    static std::map<std::string, std::string> made;  // "config extra" -> log
    const std::string key = config + " " + extra;
    if (const auto it = made.find(key); it != made.end()) return it->second;
    const std::string dir = freshDir("replay-" + config);
    const RunResult r = runScenario(kConfigs + "/" + config + ".yaml", dir, "-q --set duration=1 " + extra);
    if (r.exit_code != 0)
      throw std::runtime_error("recording " + key + " failed: exit " + std::to_string(r.exit_code) + "\n" +
                               r.output);
    return made[key] = dir + "/run.lcm";
  }
  static const std::string& chainLog() { return recording("chain_m2", ""); }
  static const std::string& flexibleLog() { return recording("flexible_2dof_filtered_rate", ""); }
  static const std::string& realtimeLog() { return recording("chain_m1", "--mode realtime"); }
};

// Offset of the first event (LCM sync word 0xEDA1DA01) at or after `from`, so
// the damage below lands at the same place in every recording: where events
// fall depends on the run (realtime timing, string lengths), and junk that
// lands wholly inside one payload is not detectable at all (LCM logs have no
// checksums).
std::uintmax_t eventStartAtOrAfter(const std::string& log, std::uintmax_t from) {
  std::ifstream in(log, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = bytes.find(std::string("\xED\xA1\xDA\x01", 4), from);
  EXPECT_NE(at, std::string::npos) << "no event after byte " << from << " of " << log;
  return at == std::string::npos ? from : at;
}

TEST_F(Recorded, LockstepAndRealtimeLogsReplayExactly) {
  for (const std::string& log : {chainLog(), flexibleLog(), realtimeLog()})
    for (const std::string component : {"controller", "actuator", "plant"}) {
      const RunResult r = lagrange("replay " + quote(log) + " --component " + component);
      EXPECT_EQ(r.exit_code, 0) << log << ": " << r.output;
      EXPECT_NE(r.output.find(component + " reproduced all"), std::string::npos) << r.output;
    }
}

// Issue #46: replay wanted run.lcm where report, export and view take the
// run's folder; now it takes either, with the same result.
TEST_F(Recorded, ARunsFolderReplaysAsItsLog) {
  const std::string log = chainLog();
  const RunResult by_log = lagrange("replay " + quote(log));
  const RunResult by_folder = lagrange("replay " + quote(std::filesystem::path(log).parent_path().string()));
  EXPECT_EQ(by_folder.exit_code, 0) << by_folder.output;
  EXPECT_EQ(by_folder.output, by_log.output);
  const std::string empty_folder = freshDir("replay-empty-folder");
  std::filesystem::create_directories(empty_folder);
  const RunResult empty = lagrange("replay " + quote(empty_folder) + " 2>&1");
  EXPECT_EQ(empty.exit_code, 2) << empty.output;
  EXPECT_NE(empty.output.find("run.lcm"), std::string::npos) << empty.output;
}

// The actuator's replay has teeth too: a saturation limit it did not have
// clips the first torque step that exceeds it.
TEST_F(Recorded, TheActuatorReplayCatchesAChangedSaturation) {
  const RunResult r =
      lagrange("replay " + quote(chainLog()) + " --component actuator --set actuator.saturation=5");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("ACTUATOR_STATE.tau_applied[1][1]: recorded -13.01920363834606, replayed -5"),
            std::string::npos)
      << r.output;
}

// The replay test has teeth: a changed gain fails at the first tick it can
// change. kp0 enters u at once (tick 0); the filter pole a0 first matters at
// tick 2 (bumpless start: qc(1) = -b q~(0) whatever a0 is).
TEST_F(Recorded, APerturbedGainDivergesAtTheRightTick) {
  const RunResult kp = lagrange("replay " + quote(chainLog()) + " --set controller.kp=[150.001,10]");
  EXPECT_EQ(kp.exit_code, 1) << kp.output;
  EXPECT_NE(kp.output.find("at tick 0 (t = 0.000000 s): CONTROL_COMMAND.u[1]: recorded"), std::string::npos)
      << kp.output;
  const RunResult pole = lagrange("replay " + quote(chainLog()) + " --set controller.a=[50.001,50]");
  EXPECT_EQ(pole.exit_code, 1) << pole.output;
  EXPECT_NE(pole.output.find("at tick 2 (t = 0.002000 s): CONTROL_COMMAND."), std::string::npos)
      << pole.output;
  const RunResult stage =
      lagrange("replay " + quote(flexibleLog()) + " --set controller.motor_rate_pole=301");
  EXPECT_EQ(stage.exit_code, 1) << stage.output;
  EXPECT_NE(stage.output.find("DIVERGED"), std::string::npos) << stage.output;
}

TEST_F(Recorded, ATruncatedLogReplaysWhatWasRecorded) {
  const std::string cut = freshDir("truncated") + ".lcm";
  const auto size = std::filesystem::file_size(chainLog());
  std::filesystem::copy_file(chainLog(), cut);
  std::filesystem::resize_file(cut, eventStartAtOrAfter(chainLog(), size / 2) + 7);  // mid-header
  const RunResult r = lagrange("replay " + quote(cut));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("reproduced all"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("1001 recorded outputs"), std::string::npos)
      << r.output;  // fewer than the full run
  EXPECT_NE(r.output.find("warning: the log ends with"), std::string::npos) << r.output;  // and says why
  EXPECT_NE(r.output.find("not a whole event"), std::string::npos) << r.output;
  const RunResult plant = lagrange("replay " + quote(cut) + " --component plant");
  EXPECT_EQ(plant.exit_code, 0) << plant.output;

  // Garbage in the middle: the reader skips to the next event and says how much it lost.
  const std::string corrupt = freshDir("corrupt") + ".lcm";
  std::filesystem::copy_file(chainLog(), corrupt);
  {
    std::fstream f(corrupt, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(eventStartAtOrAfter(chainLog(), size / 3)));
    const std::string junk(300, '\x5a');
    f.write(junk.data(), static_cast<std::streamsize>(junk.size()));
  }
  // The junk starts on an event's sync word, so that event and whatever else
  // the 300 bytes cover are lost; the event the junk ends in keeps no header,
  // so the reader must find the next sync word. The replay then passes with a
  // few commands fewer, or names what the junk destroyed -- an input, or a
  // command, which it must not take for a divergence (#44) -- and where the
  // junk is. Either way it warns, and reading goes on past the junk.
  const RunResult c = lagrange("replay " + quote(corrupt));
  EXPECT_NE(c.output.find("corrupt bytes between events were skipped"), std::string::npos) << c.output;
  std::smatch replayed;  // all but the few commands the junk destroyed
  const bool nearly_all = std::regex_search(c.output, replayed, std::regex("reproduced all ([0-9]+)")) &&
                          std::stoll(replayed[1]) >= 1001 - 3;
  EXPECT_TRUE(nearly_all || (c.exit_code == 2 && c.output.find("the log lacks") != std::string::npos &&
                             c.output.find("corrupt bytes skipped at byte") != std::string::npos))
      << c.output;
  EXPECT_EQ(c.output.find("DIVERGED"), std::string::npos) << c.output;
  const std::string report_dir = freshDir("corrupt-report");
  const RunResult report = lagrange("report " + quote(corrupt) + " -o " + quote(report_dir));
  EXPECT_EQ(report.exit_code, 0) << report.output;
  EXPECT_NE(report.output.find("corrupt bytes between events were skipped"), std::string::npos)
      << report.output;
  long long rows = 0;  // the events behind the junk are read too: only a few ticks are lost
  std::ifstream truth(report_dir + "/PLANT_TRUTH.csv");
  for (std::string line; std::getline(truth, line);) ++rows;
  EXPECT_GE(rows, 1 + 1001 - 3) << report.output;
}

// lagrange report: a CSV per channel, one row per tick, values exact.
TEST_F(Recorded, ReportWritesOneCsvPerChannelWithEveryTick) {
  const std::string out = freshDir("csv");
  const RunResult r = lagrange("report " + quote(std::filesystem::path(chainLog()).parent_path().string()) +
                               " -o " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream truth(out + "/PLANT_TRUTH.csv");
  std::string header, first;
  std::getline(truth, header);
  std::getline(truth, first);
  EXPECT_EQ(header.rfind("tick,sim_time,q[1],q[2],qdot[1],qdot[2],tau_applied[1]", 0), 0u) << header;
  EXPECT_EQ(first.rfind("0,0,2,-1.5,", 0), 0u) << first;  // chain_m2.yaml starts at q = (2, -1.5)
  long long lines = 2;
  for (std::string line; std::getline(truth, line);) ++lines;
  EXPECT_EQ(lines, 1 + 1001);  // header + ticks 0..1000
  std::ifstream command(out + "/CONTROL_COMMAND.csv");
  std::getline(command, header);
  EXPECT_NE(header.find("xi_error[2][1]"), std::string::npos) << header;  // m = 2 chain errors

  const std::string text = freshDir("notalog") + ".txt";
  std::ofstream(text) << "hello\n";
  const RunResult bad = lagrange("report " + quote(text));
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("is not an LCM log: no event in its 6 bytes"), std::string::npos) << bad.output;
}

TEST(ReplayBadInput, ALogWithoutScenarioOrNotALogIsNamed) {
  const std::string no_scenario = freshDir("noscenario") + ".lcm";
  {
    lcm::LogFile log(no_scenario, "w");
    lcm::LogEvent ev{};
    std::string payload = "not a lagrange message";
    ev.channel = "PLANT_POSITION";
    ev.data = payload.data();
    ev.datalen = static_cast<int32_t>(payload.size());
    log.writeEvent(&ev);
  }
  const RunResult r = lagrange("replay " + quote(no_scenario));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no SCENARIO channel among its 1 events on PLANT_POSITION"), std::string::npos)
      << r.output;
  EXPECT_NE(
      r.output.find("1 event of this project's channels cannot be used (1 on PLANT_POSITION; the first, "
                    "at byte 0, does not decode as plant_position_t"),
      std::string::npos)
      << r.output;

  const std::string text = freshDir("text") + ".lcm";
  std::ofstream(text) << "name: not a log\n";
  const RunResult t = lagrange("replay " + quote(text));
  EXPECT_EQ(t.exit_code, 2) << t.output;
  EXPECT_NE(t.output.find("is not an LCM log: no event in its 16 bytes"), std::string::npos) << t.output;

  // Another project's log: its channels are named, nothing is decoded as ours.
  const std::string foreign = freshDir("foreign") + ".lcm";
  {
    lcm::LogFile log(foreign, "w");
    for (const char* channel : {"POSE", "ODOMETRY", "POSE"}) {
      lcm::LogEvent ev{};
      std::string payload = "\x01\x02\x03 someone else's bytes";
      ev.channel = channel;
      ev.data = payload.data();
      ev.datalen = static_cast<int32_t>(payload.size());
      log.writeEvent(&ev);
    }
  }
  for (const std::string component : {"controller", "actuator", "plant"}) {
    const RunResult f = lagrange("replay " + quote(foreign) + " --component " + component);
    EXPECT_EQ(f.exit_code, 2) << f.output;
    EXPECT_NE(f.output.find("no SCENARIO channel among its 3 events on ODOMETRY, POSE"), std::string::npos)
        << f.output;
  }
  const RunResult fr = lagrange("report " + quote(foreign) + " -o " + quote(freshDir("foreign-report")));
  EXPECT_EQ(fr.exit_code, 2) << fr.output;
  EXPECT_NE(fr.output.find("holds no message of this project among its 3 events on ODOMETRY, POSE"),
            std::string::npos)
      << fr.output;
}

}  // namespace
}  // namespace lagrange::testing
