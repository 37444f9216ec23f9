// What a run folder or a log can make a reader do (docs/reliability.md,
// "What a run folder and a log can make a reader do"): the attacks of issue
// #53, each made by the test itself and each refused or harmless.
//
// RunFolder: a folder's lcm.json is data. A URL other than the launcher's
// form (LCM's file provider in write mode empties a file), a namespace pid
// that is not the launcher's, a FIFO: refused by `view` and `spy`, naming
// the file and the field, before anything is opened.
//
// LoggedUrdf: a log's scenario names no file its readers open. Its arm is
// the URDF copy it carries (robot.urdf.xml); a `robot.urdf.file` naming a
// file of the test's (watched with inotify: any open of it is seen) is never
// opened by replay, report, export or view, with or without the copy, nor
// an `extends`; only the user's --set robot.urdf.file is read.
//
// TerminalText: text from a file or a program reaches the terminal with its
// control characters escaped (util/terminal_text.hpp): an error quoting a
// file, the run's result block; tests/integration/terminal_text_test.cpp
// has the commands that print names and programs' lines.
//
// ViewHost: the viewer answers a request with exactly one Host header of
// printable ASCII naming it; two (the allowed one first or last) or one
// holding a NUL (`localhost\0.evil.example`, which a reader of the first
// header cut at the NUL took for `localhost`) are refused.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "config/scenario.hpp"
#include "lagrange/scenario_t.hpp"
#include "logs/log_reader.hpp"
#include "support/configs.hpp"
#include "support/log_events.hpp"
#include "support/temp_dir.hpp"
#include "tools/command_error.hpp"
#include "tools/export/export.hpp"
#include "tools/replay/replay_log.hpp"
#include "tools/report/report.hpp"
#include "tools/run/run_outcome.hpp"
#include "tools/spy/spy.hpp"
#include "tools/view/view.hpp"
#include "tools/view/view_host_check.hpp"
#include "tools/view/view_source.hpp"
#include "transport/channels.hpp"
#include "util/error.hpp"
#include "util/terminal_text.hpp"
#include "wiring/netns.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A process whose first argument's file name is `lagrange` (a link to
// sleep): what launcherAlive takes for a going run's launcher, as any live
// `lagrange` process of the user's would be. Killed with the object.
class FakeLauncher {
 public:
  explicit FakeLauncher(const std::string& dir) {
    const std::string link = dir + "/bin/lagrange";
    fs::create_directories(dir + "/bin");
    fs::create_symlink("/bin/sleep", link);
    pid_ = fork();
    if (pid_ == 0) {
      execl(link.c_str(), link.c_str(), "60", static_cast<char*>(nullptr));
      _exit(127);
    }
    // Until the exec has replaced the test's image in /proc/PID/cmdline.
    for (int i = 0; i < 200 && !tools::launcherAlive(pid_); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ~FakeLauncher() {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
};

// What a command run in a child process printed and returned; the child is
// killed after `seconds` (a view that went live would serve for ever).
struct Outcome {
  int exit_code = -1;  ///< -1: it was still running and was killed
  std::string out, err;
};

template <class Command>
Outcome inChild(const std::string& dir, const Command& command, double seconds = 20) {
  const std::string out = dir + "/child.out", err = dir + "/child.err";
  const pid_t pid = fork();
  if (pid == 0) {
    if (!freopen(out.c_str(), "w", stdout) || !freopen(err.c_str(), "w", stderr)) _exit(126);
    const int code = command();
    std::fflush(stdout);
    std::fflush(stderr);
    _exit(code);
  }
  Outcome o;
  int status = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > end) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      o.out = readAll(out);
      o.err = readAll(err);
      return o;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  o.out = readAll(out);
  o.err = readAll(err);
  return o;
}

class RunFolder : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    run_ = dir_ + "/run";
    fs::create_directories(run_);
    std::ofstream(run_ + "/run.key") << std::string(64, 'a') << "\n";
    fs::permissions(run_ + "/run.key", fs::perms::owner_read | fs::perms::owner_write);
    std::ofstream(run_ + "/run.lcm") << "not read: the folder's lcm.json is refused first";
    std::ofstream(victim_ = dir_ + "/victim", std::ios::binary) << kVictimBytes;
  }
  void writeEndpointText(const std::string& text) { std::ofstream(run_ + "/lcm.json") << text; }
  static constexpr const char* kVictimBytes =
      "the victim's bytes, which no reader of a run folder may touch\n";
  std::string run_, victim_;
};

// The attack of issue #53: a folder whose lcm.json names LCM's file
// provider in write mode, beside a run.key and a run.lcm, its launcher_pid a
// live `lagrange`. Before, `view` went live and the victim was emptied;
// `spy --print-command` handed the URL on to lcm-spy.
TEST_F(RunFolder, AFileUrlInLcmJsonIsRefusedByViewAndSpyAndTheVictimKeepsItsBytes) {
  FakeLauncher launcher(dir_);
  ASSERT_TRUE(tools::launcherAlive(launcher.pid())) << "the attack needs a live `lagrange` as launcher";
  const std::string url = "file://" + victim_ + "?mode=w";
  writeEndpointText(R"({"lcm_url": ")" + url + R"(", "run_id": 1, "netns_pid": null, "launcher_pid": )" +
                    std::to_string(launcher.pid()) + "}");

  tools::ViewOptions view;
  view.source = run_;
  view.port = 0;
  const Outcome v = inChild(dir_, [&] { return tools::runView(view); });
  EXPECT_EQ(v.exit_code, 2) << v.out << v.err;
  EXPECT_NE(v.err.find(run_ + "/lcm.json: lcm_url '" + url + "' is refused: it is not a udpm:// URL"),
            std::string::npos)
      << v.err;
  EXPECT_NE(v.err.find("expected the URL `lagrange run` writes, udpm://A.B.C.D:PORT?ttl=N"),
            std::string::npos)
      << v.err;
  EXPECT_EQ(readAll(victim_), kVictimBytes) << "the victim file was touched";

  tools::SpyOptions spy;
  spy.run_dir = run_;
  spy.print_only = true;
  const Outcome s = inChild(dir_, [&] { return tools::runSpy(spy); });
  EXPECT_EQ(s.exit_code, 2) << s.out << s.err;
  EXPECT_EQ(s.out.find("file:"), std::string::npos) << "the URL was handed on to lcm-spy: " << s.out;
  EXPECT_NE(s.err.find("lcm.json: lcm_url"), std::string::npos) << s.err;
  EXPECT_EQ(readAll(victim_), kVictimBytes);

  // The user's own URL on the command line is the user's: the folder's is not read for it,
  // but the folder is still refused whole (its namespace pid would be followed).
  spy.lcm_url = "udpm://239.255.76.67:7667?ttl=0";
  EXPECT_EQ(inChild(dir_, [&] { return tools::runSpy(spy); }).exit_code, 2);

  // The same folder with the launcher's own URL form is a live run's.
  writeEndpointText(R"({"lcm_url": "udpm://239.255.76.67:7667?ttl=0", "run_id": 1, "netns_pid": null, )"
                    R"("launcher_pid": )" +
                    std::to_string(launcher.pid()) + "}");
  spy.lcm_url.clear();
  const Outcome ok = inChild(dir_, [&] { return tools::runSpy(spy); });
  if (ok.err.find("lagrange_lcmtypes.jar not found") != std::string::npos) {
    // A build without Java (the sanitizer pass): the folder passed; what is
    // missing is lcm-spy's jar of the project's types, not the folder's say.
    EXPECT_EQ(ok.err.find("lcm.json"), std::string::npos) << ok.err;
    return;
  }
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find(" --lcm-url=udpm://239.255.76.67:7667?ttl=0\n"), std::string::npos) << ok.out;
}

// Only the form the launcher writes: wiring::freshLcmUrl's, or a user's
// --lcm-url of that form (TTL 1 across hosts); every near miss is refused.
TEST_F(RunFolder, OnlyTheLaunchersUrlFormPasses) {
  const std::string kNulInside("udpm://239.255.76.67:7667?ttl=0\0.evil", 37);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(tools::runUrlProblem(wiring::freshLcmUrl()), "");
  for (const std::string url : {"udpm://239.255.76.67:7667?ttl=1", "udpm://239.255.76.67:7667",
                                "udpm://224.0.0.1:1?ttl=255", "udpm://239.255.255.255:65535?ttl=0"})
    EXPECT_EQ(tools::runUrlProblem(url), "") << url;
  for (const std::string& url : {std::string("file:///etc/passwd?mode=w"),
                                 std::string("memq://"),
                                 std::string("tcpq://127.0.0.1:7700"),
                                 std::string("UDPM://239.255.76.67:7667?ttl=0"),
                                 std::string(" udpm://239.255.76.67:7667?ttl=0"),
                                 std::string("udpm://239.255.76.67:7667?ttl=0 "),
                                 std::string("udpm://239.255.76.67:7667?ttl=0\n"),
                                 std::string("udpm://239.255.76.67:7667?ttl=0\0.evil",
                                             sizeof "udpm://239.255.76.67:7667?ttl=0\0.evil" - 1),
                                 std::string("udpm://10.0.0.1:7667?ttl=0"),
                                 std::string("udpm://240.0.0.1:7667?ttl=0"),
                                 std::string("udpm://239.255.076.67:7667?ttl=0"),
                                 std::string("udpm://239.255.76:7667?ttl=0"),
                                 std::string("udpm://239.255.76.67.1:7667?ttl=0"),
                                 std::string("udpm://239.255.76.256:7667?ttl=0"),
                                 std::string("udpm://239.255.76.67:0?ttl=0"),
                                 std::string("udpm://239.255.76.67:65536?ttl=0"),
                                 std::string("udpm://239.255.76.67:07667?ttl=0"),
                                 std::string("udpm://239.255.76.67?ttl=0"),
                                 std::string("udpm://239.255.76.67:7667?ttl=256"),
                                 std::string("udpm://239.255.76.67:7667?ttl="),
                                 std::string("udpm://239.255.76.67:7667?ttl=0&ttl=1"),
                                 std::string("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=1"),
                                 std::string("udpm://239.255.76.67:7667?mode=w"),
                                 std::string("udpm://239.255.76.67:7667?"),
                                 std::string("udpm://239.255.76.67:7667/x"),
                                 std::string("udpm://user@239.255.76.67:7667"),
                                 std::string("udpm://[ff02::1]:7667"),
                                 std::string("udpm://0xef.255.76.67:7667")})
    EXPECT_NE(tools::runUrlProblem(url), "") << "accepted: " << url;
}

// The rest of lcm.json is as strict: the launcher writes netns_pid as its
// own pid (or null), so a folder naming another process's namespace (which
// spy and view would join) is refused; as are pids that are no pids, fields
// the launcher does not write, and files that are not regular.
TEST_F(RunFolder, EveryFieldOfLcmJsonIsCheckedAndNonRegularFilesAreRefusedUnread) {
  const auto refusal = [&](const std::string& text) {
    writeEndpointText(text);
    try {
      tools::readEndpoint(run_);
    } catch (const BadInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string url = R"("lcm_url": "udpm://239.255.76.67:7667?ttl=0")";
  EXPECT_NE(refusal("{" + url + R"(, "run_id": 1, "netns_pid": 1, "launcher_pid": 4240})")
                .find("netns_pid 1 is not the launcher_pid 4240"),
            std::string::npos);
  for (const std::string pid : {"0", "-1", "1.5", "\"42\"", "99999999999"})
    EXPECT_NE(refusal("{" + url + R"(, "run_id": 1, "netns_pid": null, "launcher_pid": )" + pid + "}")
                  .find("launcher_pid is"),
              std::string::npos)
        << pid;
  EXPECT_NE(refusal("{" + url + R"(, "netns_pid": -1})").find("netns_pid is -1"), std::string::npos);
  EXPECT_NE(refusal("{" + url + R"(, "netns_pid": null, "extends": "x"})").find("it has the field extends"),
            std::string::npos);
  EXPECT_NE(refusal("{" + url + R"(, "run_id": "1", "netns_pid": null})").find("run_id is not an integer"),
            std::string::npos);
  EXPECT_EQ(refusal("{" + url + R"(, "run_id": 7, "netns_pid": 4242, "launcher_pid": 4242})"), "");

  // A FIFO would block a reader for ever; a directory or a device is no lcm.json either.
  fs::remove(run_ + "/lcm.json");
  ASSERT_EQ(mkfifo((run_ + "/lcm.json").c_str(), 0600), 0);
  const Outcome fifo = inChild(
      dir_,
      [&] {
        try {
          tools::readEndpoint(run_);
        } catch (const BadInput& e) {
          std::fprintf(stderr, "%s\n", e.what());
          return 2;
        }
        return 0;
      },
      10);
  EXPECT_EQ(fifo.exit_code, 2) << "a FIFO as lcm.json blocked or was read: " << fifo.err;
  EXPECT_NE(fifo.err.find("is a FIFO (named pipe)"), std::string::npos) << fifo.err;
}

// spy joins only a live launcher's namespace: a file that names a namespace
// pid without its launcher (as files written before launcher_pid existed
// did) names a run long ended, whatever process has that pid now.
TEST_F(RunFolder, SpyJoinsNoNamespaceButALiveLaunchersOwn) {
  writeEndpointText(R"({"lcm_url": "udpm://239.255.76.67:7667?ttl=0", "run_id": 1, "netns_pid": )" +
                    std::to_string(getpid()) + "}");
  tools::SpyOptions spy;
  spy.run_dir = run_;
  const Outcome s = inChild(dir_, [&] { return tools::runSpy(spy); });
  EXPECT_EQ(s.exit_code, 2) << s.err;
  EXPECT_NE(s.err.find("has ended"), std::string::npos) << s.err;
}

// Every open of one file, seen through inotify from when the watch is made.
class OpenWatch {
 public:
  explicit OpenWatch(const std::string& path) : fd_(inotify_init1(IN_NONBLOCK | IN_CLOEXEC)) {
    watch_ = inotify_add_watch(fd_, path.c_str(), IN_OPEN | IN_ACCESS);
  }
  ~OpenWatch() { close(fd_); }
  OpenWatch(const OpenWatch&) = delete;
  OpenWatch& operator=(const OpenWatch&) = delete;
  bool watching() const { return fd_ >= 0 && watch_ >= 0; }
  /// The opens (and reads) seen since the last call.
  int opens() {
    int n = 0;
    alignas(inotify_event) char buf[4096];
    for (ssize_t got; (got = read(fd_, buf, sizeof buf)) > 0;)
      for (char* p = buf; p < buf + got;
           p += sizeof(inotify_event) + reinterpret_cast<inotify_event*>(p)->len)
        n += (reinterpret_cast<inotify_event*>(p)->mask & IN_OPEN) != 0;
    return n;
  }

 private:
  int fd_;
  int watch_ = -1;
};

class LoggedUrdf : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    events_ = readEvents(kGoldenDir + "panda_theorem1_lockstep.lcm");
    for (const LoggedEvent& e : events_)
      if (e.channel == transport::kScenario) {
        yaml_ = decodeAs<lagrange::scenario_t>(e).yaml;
        break;
      }
    ASSERT_FALSE(yaml_.empty());
    embedded_xml_ = YAML::Load(yaml_)["robot"]["urdf"]["xml"].as<std::string>();
    // The file the crafted logs name: a URDF whose joints are named apart
    // (marker_joint1, ...), so that an arm built from it would show.
    marker_ = dir_ + "/shadow.urdf";
    std::string marked = embedded_xml_;
    for (std::size_t at; (at = marked.find("panda_joint")) != std::string::npos;)
      marked.replace(at, 11, "marker_joint");
    std::ofstream(marker_) << marked;
  }

  // The golden Panda log with every SCENARIO edited by `edit`, as run.lcm
  // of a run folder of its own (beside a config.resolved.yaml edited alike,
  // which export reads first); the folder.
  template <class Edit>
  std::string craftedRun(const std::string& name, const Edit& edit) {
    YAML::Node root = YAML::Load(yaml_);
    edit(root);
    YAML::Emitter out;
    out << root;
    const std::string folder = dir_ + "/" + name;
    fs::create_directories(folder);
    std::vector<LoggedEvent> events = events_;
    for (LoggedEvent& e : events)
      if (e.channel == transport::kScenario) {
        lagrange::scenario_t m = decodeAs<lagrange::scenario_t>(e);
        m.yaml = out.c_str();
        e.data.assign(static_cast<std::size_t>(m.getEncodedSize()), '\0');
        m.encode(e.data.data(), 0, static_cast<int>(e.data.size()));
      }
    writeEvents(folder + "/run.lcm", events);
    std::ofstream(folder + "/config.resolved.yaml") << out.c_str();
    return folder;
  }

  // Every reader of a log, in process, on `folder`: what each said.
  struct Readings {
    std::string replay;                      ///< openLog's error, "" when it opened
    std::vector<std::string> replay_joints;  ///< the arm replay would use
    std::string report, export_warnings;     ///< their warnings, joined
    std::string view;                        ///< readViewLog's error, "" when it drew
    bool bounds_read = false;                ///< logs::readLog went through
  };
  Readings readersOf(const std::string& folder, const std::vector<std::string>& overrides = {}) {
    Readings r;
    const std::string log = folder + "/run.lcm";
    try {
      const tools::replay_log::Opened o =
          tools::replay_log::openLog(log, overrides, transport::kControlCommand);
      r.replay_joints = o.scenario.robotModel()->jointNames();
    } catch (const std::exception& e) {
      r.replay = e.what();
    }
    if (!overrides.empty()) return r;  // only replay takes --set
    fs::create_directories(folder + "/report");
    for (const std::string& w : tools::writeReport(log, folder + "/report").warnings) r.report += w + "\n";
    for (const std::string& w : tools::exportHdf5(folder, folder + "/x.h5", true).warnings)
      r.export_warnings += w + "\n";
    try {
      tools::readViewLog(log);
    } catch (const std::exception& e) {
      r.view = e.what();
    }
    logs::readLog(log, [](const lcm::LogEvent&) {});
    r.bounds_read = true;
    return r;
  }

  std::vector<LoggedEvent> events_;
  std::string yaml_, embedded_xml_, marker_;
};

// The attack of issue #53: `robot.urdf.file: /etc/shadow` and no copy of the
// URDF. Before, replay, export and view opened and parsed the file (as
// root: any file). Now none opens it: replay refuses naming the missing
// copy, report and export say why the scenario does not read, view draws
// from ROBOT_DESCRIPTION.
TEST_F(LoggedUrdf, AFileTheLogNamesWithoutItsCopyIsNeverOpenedAndTheCopyIsNamedMissing) {
  const std::string run = craftedRun("no_copy", [&](YAML::Node& root) {
    root["robot"]["urdf"].remove("xml");
    root["robot"]["urdf"]["file"] = marker_;
  });
  OpenWatch watch(marker_);
  ASSERT_TRUE(watch.watching());
  const Readings r = readersOf(run);
  EXPECT_EQ(watch.opens(), 0) << "a reader opened the file the log names";
  const std::string missing =
      "robot.urdf.xml: missing: the recorded scenario names the URDF file '" + marker_ +
      "' but carries no copy of its URDF, and a reader of a log opens no file the log names";
  EXPECT_NE(r.replay.find(missing), std::string::npos) << r.replay;
  EXPECT_NE(r.report.find(missing), std::string::npos) << r.report;
  EXPECT_NE(r.export_warnings.find(missing), std::string::npos) << r.export_warnings;
  EXPECT_EQ(r.view, "") << "the arm is drawn from the log's ROBOT_DESCRIPTION";
  EXPECT_TRUE(r.bounds_read);

  // Replay reads the log's own scenario first (the shape of its messages), which lacks its arm:
  // refused also when the user names a URDF (every log of `lagrange run` has the copy).
  EXPECT_NE(readersOf(run, {"robot.urdf.file=" + marker_}).replay.find(missing), std::string::npos);
}

// A log that names a file and carries its copy: every reader uses the copy,
// and the file is never opened.
TEST_F(LoggedUrdf, ReadersUseTheLogsOwnCopyAndNeverOpenTheFileItNames) {
  const std::string run =
      craftedRun("with_copy", [&](YAML::Node& root) { root["robot"]["urdf"]["file"] = marker_; });
  OpenWatch watch(marker_);
  ASSERT_TRUE(watch.watching());
  const Readings r = readersOf(run);
  EXPECT_EQ(watch.opens(), 0) << "a reader opened the file the log names";
  EXPECT_EQ(r.replay, "");
  ASSERT_FALSE(r.replay_joints.empty());
  EXPECT_EQ(r.replay_joints.front(), "panda_joint1") << "the arm is not the log's own copy";
  EXPECT_EQ(r.report.find("not a valid scenario"), std::string::npos) << r.report;
  EXPECT_EQ(r.export_warnings.find("joint_names left out"), std::string::npos) << r.export_warnings;
  EXPECT_EQ(r.view, "");

  // The file the user names replaces the copy.
  const Readings mine = readersOf(run, {"robot.urdf.file=" + marker_});
  EXPECT_GT(watch.opens(), 0);
  ASSERT_FALSE(mine.replay_joints.empty());
  EXPECT_EQ(mine.replay_joints.front(), "marker_joint1");
}

// `extends` in a log's scenario would have its readers open (and merge) a
// file the log names: refused, the file unopened.
TEST_F(LoggedUrdf, AnExtendsInALogsScenarioIsRefusedUnopened) {
  const std::string base = dir_ + "/base.yaml";
  std::ofstream(base) << "description: the base a log names\n";
  OpenWatch watch(base);
  ASSERT_TRUE(watch.watching());
  const std::string run = craftedRun("extends", [&](YAML::Node& root) { root["extends"] = base; });
  // A file named as the readers name the scenario's source: the folder a relative extends would be read from.
  std::ofstream(run + "/run.lcm:SCENARIO") << "name: x\n";
  const Readings r = readersOf(run);
  EXPECT_EQ(watch.opens(), 0) << "a reader opened the file the log's extends names";
  EXPECT_NE(
      r.replay.find("extends: a recorded scenario is the resolved one a run wrote, which has no extends"),
      std::string::npos)
      << r.replay;
  EXPECT_NE(r.report.find("extends: a recorded scenario"), std::string::npos) << r.report;
}

// The escapes of issue #53: a title (OSC 0), a clear screen (CSI 2J), a
// bell, a carriage return that would overwrite the line, and a C1 CSI.
const std::string kHostile = "\x1b]0;owned\x07\x1b[2J\rfake line\xc2\x9b";
const std::string kShown = "\\x1b]0;owned\\x07\\x1b[2J\\x0dfake line\\xc2\\x9b";

TEST(TerminalText, LinesAndTabsKeptOnlyWhereAskedEverythingElseEscaped) {
  EXPECT_EQ(util::terminalSafe(kHostile), kShown);
  EXPECT_EQ(util::terminalSafeLines(kHostile + "\n\tnext"), kShown + "\n\tnext");
  EXPECT_EQ(util::terminalSafe("a\nb\tc"), "a\\x0ab\\x09c");
  EXPECT_EQ(util::terminalSafeLines(util::terminalSafeLines(kHostile)), kShown)
      << "escaping twice adds nothing";
  EXPECT_EQ(util::terminalSafeLines("Loría ü ‖q̃‖"), "Loría ü ‖q̃‖");
}

// Every command ends on an error through failWith: a message quoting a
// scenario's key, a log's value or a program's words is printed escaped.
TEST(TerminalText, AnErrorQuotingAFileIsPrintedEscaped) {
  ::testing::internal::CaptureStderr();
  const int code =
      tools::failWith("lagrange check-gains",
                      BadInput("config: x.yaml: unknown key '" + kHostile + "'\nexpected one of name, ..."));
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, 2);
  EXPECT_EQ(
      err, "lagrange check-gains: config: x.yaml: unknown key '" + kShown + "'\nexpected one of name, ...\n");
}

// `lagrange run`'s block: every string of summary.json (the gain check's
// why, the scenario's name, the verdict's sentences) printed escaped.
TEST(TerminalText, TheRunsResultBlockEscapesEveryStringOfItsSummary) {
  const nlohmann::json j = {{"scenario", "name " + kHostile},
                            {"status", "completed"},
                            {"tracking",
                             {{"final_error", 1e-5},
                              {"tolerance", 1e-3},
                              {"convergence_time", 0.5},
                              {"convergence_deadline", 5.0},
                              {"met", true},
                              {"samples", 1000}}},
                            {"torque", {{"max_abs", 1.0}}},
                            {"gains", {{"checked", false}, {"why", "why " + kHostile}}},
                            {"timing", {{"sim_time", 1.0}, {"wall_time", 1.0}}},
                            {"verdict",
                             {{"headline", "tracking met"},
                              {"met", true},
                              {"warnings", {{{"kind", "x"}, {"text", "w " + kHostile}}}}}}};
  const std::string block = tools::resultText(j);
  for (const char c : {'\x1b', '\x07', '\r'}) EXPECT_EQ(block.find(c), std::string::npos) << block;
  EXPECT_EQ(block.find("\xc2\x9b"), std::string::npos) << block;
  EXPECT_NE(block.find("scenario name " + kShown + ": completed"), std::string::npos) << block;
  EXPECT_NE(block.find("not checked (why " + kShown + ")"), std::string::npos) << block;
  EXPECT_NE(block.find("- w " + kShown), std::string::npos) << block;
}

TEST(ViewHost, ExactlyOnePrintableHostHeaderNamingTheViewerIsAnswered) {
  const tools::HostPolicy policy = tools::hostPolicy("127.0.0.1", false);
  using Hosts = std::vector<std::string>;
  for (const Hosts& ok :
       {Hosts{"localhost"}, Hosts{"127.0.0.1:8642"}, Hosts{"[::1]:9000"}, Hosts{"LocalHost"}})
    EXPECT_EQ(tools::hostRefusal(ok, policy), "") << ok.front();
  EXPECT_NE(tools::hostRefusal({}, policy).find("no Host header"), std::string::npos);
  for (const Hosts& two : {Hosts{"localhost", "evil.example"}, Hosts{"evil.example", "localhost"},
                           Hosts{"localhost", "localhost"}})
    EXPECT_NE(tools::hostRefusal(two, policy).find("the request has 2 Host headers; exactly one is answered"),
              std::string::npos)
        << two.front() << ", " << two.back();
  const std::string nul("localhost\0.evil.example", 23);
  EXPECT_NE(tools::hostRefusal({nul}, policy).find("holds the byte 0x00 at 9, which is not printable ASCII"),
            std::string::npos);
  for (const std::string bad : {"local host", "localhost\t", "localhost\x7f", "localhost\r",
                                "l\xc3\xb6"
                                "calhost",
                                "localhost\x1b[2J"})
    EXPECT_NE(tools::hostRefusal({bad}, policy).find("not printable ASCII"), std::string::npos) << bad;
}

}  // namespace
}  // namespace lagrange::testing
