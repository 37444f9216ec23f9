// What a run folder or a log can make a reader do (docs/reliability.md,
// "What a run folder and a log can make a reader do"): the attacks of issue
// #53, each made by the test itself and each refused or harmless.
//
// RunFolder: a folder's lcm.json is data. A URL other than the launcher's
// form (LCM's file provider in write mode empties a file), a namespace pid
// that is not the launcher's, a FIFO: refused by `view` and `spy`, naming
// the file and the field, before anything is opened.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/temp_dir.hpp"
#include "tools/spy/spy.hpp"
#include "tools/view/view.hpp"
#include "util/error.hpp"
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

}  // namespace
}  // namespace lagrange::testing
