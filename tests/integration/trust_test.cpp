// Output you can trust: one run per output directory, no writing through a
// planted link, a full disk named, and a log that says what it lacks.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <tuple>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/signal_run.hpp"
#include "transport/channels.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

nlohmann::json summaryOf(const std::string& dir) {
  return nlohmann::json::parse(std::ifstream(fs::path(dir) / "summary.json"));
}

// A run in the background: its result once it has ended.
class BackgroundRun {
 public:
  BackgroundRun(const std::string& dir, const std::string& args) {
    thread_ = std::thread([this, dir, args] {
      result_ = runScenario(kRigid, dir, args);
      done_ = true;
    });
  }
  ~BackgroundRun() {
    if (thread_.joinable()) thread_.join();
  }
  bool done() const { return done_; }
  RunResult join() {
    thread_.join();
    return result_;
  }

 private:
  std::thread thread_;
  std::atomic<bool> done_{false};
  RunResult result_;
};

// Waits until DIR/run.lcm holds `bytes` (the run is under way); false if the run ended first.
bool waitForLog(const std::string& dir, const BackgroundRun& run, std::uintmax_t bytes) {
  const fs::path log = fs::path(dir) / "run.lcm";
  const auto until = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < until && !run.done()) {
    std::error_code ec;
    if (fs::file_size(log, ec) >= bytes && !ec) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// Two runs into one directory: the second is refused (exit 2) naming the
// directory and the first run's pid, and the first run's outputs are its own.
TEST(Trust, SecondRunOnTheSameOutIsRefusedNamingTheHolder) {
  const std::string dir = freshDir("lock");
  BackgroundRun first(dir, "--set duration=600 -q");
  ASSERT_TRUE(waitForLog(dir, first, 50000));
  const pid_t holder = findProcess("bin/lagrange", dir);
  ASSERT_GT(holder, 0);

  const RunResult second = runScenario(kRigid, dir, "--set duration=0.5 -q");
  EXPECT_EQ(second.exit_code, 2) << second.output;
  EXPECT_NE(second.output.find("output directory '" + dir + "'"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("pid " + std::to_string(holder)), std::string::npos) << second.output;
  // compare writes its directory the same way, and is refused the same way.
  const RunResult compare =
      lagrange("compare " + quote(kConfigs + "/compare_pelican.yaml") + " --out " + quote(dir) + " -q");
  EXPECT_EQ(compare.exit_code, 2) << compare.output;
  EXPECT_NE(compare.output.find("pid " + std::to_string(holder)), std::string::npos) << compare.output;

  ASSERT_EQ(kill(holder, SIGINT), 0);
  const RunResult r = first.join();
  EXPECT_EQ(r.exit_code, 130) << r.output;
  // The first run's log is whole: one event per number, every sample once.
  lcm::LogFile log(dir + "/run.lcm", "r");
  ASSERT_TRUE(log.good());
  int64_t expected = 0;
  while (const lcm::LogEvent* ev = log.readNextEvent()) ASSERT_EQ(ev->eventnum, expected++);
  EXPECT_EQ(expected, summaryOf(dir)["log"]["events"].get<int64_t>());
}

// The lock dies with its holder: a run killed with SIGKILL leaves none behind.
TEST(Trust, KilledRunLeavesNoStaleLock) {
  const std::string dir = freshDir("stale");
  BackgroundRun first(dir, "--set duration=600 -q");
  ASSERT_TRUE(waitForLog(dir, first, 50000));
  const pid_t holder = findProcess("bin/lagrange", dir);
  ASSERT_GT(holder, 0);
  ASSERT_EQ(kill(holder, SIGKILL), 0);
  EXPECT_NE(first.join().exit_code, 0);                       // killed
  EXPECT_TRUE(fs::exists(fs::path(dir) / ".lagrange.lock"));  // the file stays; the lock did not

  const RunResult next = runScenario(kRigid, dir, "--set duration=0.3 -q");
  EXPECT_EQ(next.exit_code, 0) << next.output;
  EXPECT_EQ(summaryOf(dir)["status"], "completed");
}

// A symbolic link planted in the place of each output: refused (exit 2)
// naming it, before anything is written; the link's target keeps its bytes.
TEST(Trust, PlantedLinkIsRefusedAndItsTargetUntouched) {
  const std::string users = freshDir("users-file");
  fs::create_directories(users);
  for (const std::string name : {"run.lcm", "summary.json", "config.resolved.yaml", "gains.json", "lcm.json",
                                 "logger.log", "plant.log"}) {
    for (const std::string mode : {"lockstep", "inproc"}) {
      if (mode == "inproc" && (name == "lcm.json" || name == "logger.log" || name == "plant.log")) continue;
      const std::string dir = freshDir("link");
      fs::create_directories(dir);
      const std::string target = users + "/precious-" + name;
      const std::string bytes = "the user's own " + name + ", not to be overwritten\n";
      std::ofstream(target, std::ios::binary) << bytes;
      fs::create_symlink(target, fs::path(dir) / name);

      const RunResult r = runScenario(kRigid, dir, "--mode " + mode + " --set duration=0.3 -q");
      EXPECT_EQ(r.exit_code, 2) << name << " " << mode << ": " << r.output;
      EXPECT_NE(r.output.find("'" + dir + "/" + name + "' is a symbolic link"), std::string::npos)
          << name << " " << mode << ": " << r.output;
      EXPECT_EQ(readBytes(target), bytes) << name << " " << mode;
      EXPECT_TRUE(fs::is_symlink(fs::path(dir) / name)) << name;
      EXPECT_FALSE(fs::exists(fs::path(dir) / "run.lcm") && !fs::is_symlink(fs::path(dir) / "run.lcm"))
          << "nothing ran: " << name << " " << mode;
    }
  }
}

// report/ as a link to a directory of the user's: refused, nothing written there.
TEST(Trust, PlantedReportLinkIsRefused) {
  const std::string dir = freshDir("report-link");
  const std::string users = freshDir("users-dir");
  fs::create_directories(dir);
  fs::create_directories(users);
  fs::create_directory_symlink(users, fs::path(dir) / "report");
  const RunResult r = runScenario(kRigid, dir, "--report --set duration=0.3 -q");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'" + dir + "/report' is a symbolic link"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(users));
}

// Links planted inside report/ in the place of its files (a CSV, the
// plots script): `lagrange report` refuses (exit 2) naming the link, and the
// link's target keeps its bytes.
TEST(Trust, PlantedLinksInsideTheReportAreRefused) {
  const std::string dir = freshDir("report-inner-link");
  const RunResult run = runScenario(kRigid, dir, "--set duration=0.3 -q");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string users = freshDir("users-report-file");
  fs::create_directories(users);
  for (const std::string name : {"PLANT_TRUTH.csv", "CONTROL_COMMAND.csv", "plots.gp"}) {
    const std::string report = dir + "/report-" + fs::path(name).stem().string();
    fs::create_directories(report);
    const std::string target = users + "/precious-" + name;
    const std::string bytes = "the user's own " + name + "\n";
    std::ofstream(target, std::ios::binary) << bytes;
    fs::create_symlink(target, fs::path(report) / name);
    const RunResult r = lagrange("report " + quote(dir) + " -o " + quote(report));
    EXPECT_EQ(r.exit_code, 2) << name << ": " << r.output;
    EXPECT_NE(r.output.find("'" + report + "/" + name + "' is a symbolic link"), std::string::npos)
        << name << ": " << r.output;
    EXPECT_EQ(readBytes(target), bytes) << name;
  }
}

// A hard link to a user's file in the place of an output: the output is a
// new file; the user's file keeps its bytes (no truncation through the link).
TEST(Trust, HardLinkedOutputIsReplacedNotWrittenThrough) {
  const std::string dir = freshDir("hardlink");
  fs::create_directories(dir);
  const std::string target = dir + "/users-notes.txt";
  const std::string bytes = "the user's notes\n";
  std::ofstream(target, std::ios::binary) << bytes;
  fs::create_hard_link(target, fs::path(dir) / "summary.json");
  fs::create_hard_link(target, fs::path(dir) / "run.lcm");
  fs::create_hard_link(target, fs::path(dir) / "logger.log");
  const RunResult r = runScenario(kRigid, dir, "--set duration=0.3 -q");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(readBytes(target), bytes);
  EXPECT_EQ(summaryOf(dir)["status"], "completed");
  EXPECT_GT(readTruth(dir + "/run.lcm").size(), 100u);
}

// A full disk: the run stops with exit 1 naming run.lcm and the error, and
// what run.lcm holds up to then reads back (to its last complete event).
// A real one: a 200 kB tmpfs in a mount namespace of its own.
TEST(Trust, FullDiskStopsTheRunNamingTheFileAndKeepsWhatWasWritten) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to mount a small tmpfs";
  // Root inside a chroot (a fresh debootstrap root) has no mount namespace to
  // give: unshare cannot make "/" private there. That is the machine, not the run.
  if (const RunResult probe = shell("unshare -m true"); probe.exit_code != 0)
    GTEST_SKIP() << "no private mount namespace here: " << probe.output;
  const std::string dir = freshDir("full");
  const std::string kept = freshDir("full-kept");
  fs::create_directories(dir);
  fs::create_directories(kept);
  const std::string script = "mount -t tmpfs -o size=200k tmpfs " + quote(dir) + " || exit 99; " + kBin +
                             "/lagrange run " + quote(kRigid) + " --out " + quote(dir) +
                             " --set duration=30 -q; code=$?; df -k " + quote(dir) + "; cp " +
                             quote(dir + "/run.lcm") + " " + quote(kept + "/run.lcm") + "; exit $code";
  const RunResult r = shell("unshare -m sh -c " + quote(script));
  ASSERT_NE(r.exit_code, 99) << r.output;
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("'" + dir + "/run.lcm' failed: No space left on device"), std::string::npos)
      << r.output;
  // The disk was full: the log is what fitted, well below 30 s of samples.
  const std::uintmax_t size = fs::file_size(kept + "/run.lcm");
  EXPECT_GT(size, 100000u);
  EXPECT_LE(size, 200u * 1024u);
  const std::vector<TruthSample> truth = readTruth(kept + "/run.lcm");
  EXPECT_GT(truth.size(), 50u);
  EXPECT_LT(truth.back().t, 30.0);
  // The project's own reader reports it too (stopping at the cut).
  const RunResult report =
      lagrange("report " + quote(kept + "/run.lcm") + " --out " + quote(kept + "/report"));
  EXPECT_EQ(report.exit_code, 0) << report.output;
  EXPECT_TRUE(fs::exists(kept + "/report"));
}

// Per channel, the sequence numbers of the run's processes in a log.
struct LogNumbers {
  std::map<std::string, std::set<int64_t>> seqs;  ///< by channel (one publisher each)
  std::map<std::string, int64_t> newest;
};
LogNumbers numbersIn(const std::string& log_path, int64_t run_id) {
  LogNumbers out;
  lcm::LogFile log(log_path, "r");
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    transport::withChannelMessage(ev->channel, false, [&](auto m) {
      if (transport::safeDecode(ev->data, static_cast<size_t>(ev->datalen), m) && transport::intact(m) &&
          m.header.run_id == run_id) {
        out.seqs[ev->channel].insert(m.header.seq);
        out.newest[ev->channel] = std::max(out.newest[ev->channel], m.header.seq);
      }
      return true;
    });
  }
  return out;
}

// What the per-tick channels of a run published (the publishers' own
// counters), what the log holds and what the summary says it lacks add up.
void expectMissingMatchesTheLog(const std::string& dir) {
  const auto j = summaryOf(dir);
  const LogNumbers in_log = numbersIn(dir + "/run.lcm", j["run_id"].get<int64_t>());
  for (const auto& [channel, publisher] :
       std::map<std::string, std::string>{{"PLANT_POSITION", "plant"},
                                          {"PLANT_TRUTH", "plant"},
                                          {"CONTROL_COMMAND", "controller"},
                                          {"ACTUATOR_STATE", "actuator"}}) {
    const long long published = j["processes"][publisher]["channels"][channel]["published"].get<long long>();
    const long long recorded = static_cast<long long>(in_log.seqs.at(channel).size());
    const long long missing = j["log"]["missing_records"][channel].get<long long>();
    EXPECT_EQ(recorded + missing, published) << channel << ": " << j["log"].dump();
    // The numbers the log lacks up to its newest: all counted.
    EXPECT_GE(missing, in_log.newest.at(channel) - recorded) << channel;
  }
}

// An ordinary run: the log is complete, nothing is missing on any channel.
TEST(Trust, OrdinaryRunSaysItsLogIsComplete) {
  for (const std::string mode : {"lockstep", "realtime"}) {
    const std::string dir = freshDir("complete");
    const RunResult r = runScenario(kRigid, dir, "--mode " + mode + " --set duration=1 -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto j = summaryOf(dir);
    EXPECT_TRUE(j["log"]["complete"].get<bool>()) << mode << ": " << j["log"].dump();
    EXPECT_TRUE(j["log"]["incomplete_because"].is_null()) << mode;
    ASSERT_GE(j["log"]["missing_records"].size(), 5u) << mode << ": " << j["log"].dump();
    for (const auto& [channel, n] : j["log"]["missing_records"].items())
      EXPECT_EQ(n, 0) << mode << " " << channel;
    expectMissingMatchesTheLog(dir);
  }
}

// A realtime run whose logger is stopped (SIGSTOP) for 3 s: the others go
// on publishing, the logger's socket buffer overflows (4 MB holds about a
// second of this run's traffic). The summary says
// the log is incomplete and counts, per channel, exactly what run.lcm lacks.
TEST(Trust, StoppedLoggerIsCountedAsMissingRecords) {
  const std::string dir = freshDir("sigstop");
  BackgroundRun run(dir, "--mode realtime --set duration=6 -q");
  ASSERT_TRUE(waitForLog(dir, run, 30000));
  const pid_t logger = findProcess("lagrange-logger", dir);
  ASSERT_GT(logger, 0);
  ASSERT_EQ(kill(logger, SIGSTOP), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(3000));
  ASSERT_EQ(kill(logger, SIGCONT), 0);
  const RunResult r = run.join();
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const auto j = summaryOf(dir);
  EXPECT_FALSE(j["log"]["complete"].get<bool>()) << j["log"].dump();
  ASSERT_TRUE(j["log"]["incomplete_because"].is_string());
  EXPECT_NE(j["log"]["incomplete_because"].get<std::string>().find("not in the log"), std::string::npos);
  // The stop happened: 3 s of samples at 1 kHz did not all fit in the buffer.
  EXPECT_GT(j["log"]["missing_records"]["PLANT_TRUTH"].get<long long>(), 0) << j["log"].dump();
  EXPECT_GT(j["log"]["missing_records"]["PLANT_POSITION"].get<long long>(), 0) << j["log"].dump();
  expectMissingMatchesTheLog(dir);
}

// A run's folder is its user's: created 0700, every file in it 0600 --
// another local user reads no log, key or summary of it -- unless --share
// keeps the user's umask (docs/reliability.md).
TEST(Trust, ARunsFolderAndFilesAreTheUsersAloneUnlessShared) {
  namespace fs = std::filesystem;
  const mode_t was = ::umask(022);  // the usual umask, under which files were world-readable
  const std::string dir = freshDir("trust-private-folder");
  const RunResult r = runScenario(kRigid, dir, "--set duration=0.05 --set mode=lockstep -q");
  const std::string shared = freshDir("trust-shared-folder");
  const RunResult s = runScenario(kRigid, shared, "--set duration=0.05 --set mode=lockstep -q --share");
  ::umask(was);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(s.exit_code, 0) << s.output;
  const auto others = fs::perms::group_all | fs::perms::others_all;
  EXPECT_EQ(fs::status(dir).permissions() & others, fs::perms::none);
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.status().permissions() & others, fs::perms::none) << entry.path();
  }
  EXPECT_GE(files, 5);  // run.lcm, summary.json, the processes' logs...
  EXPECT_NE(fs::status(shared + "/summary.json").permissions() & fs::perms::others_read, fs::perms::none);
}

}  // namespace
}  // namespace lagrange::testing
