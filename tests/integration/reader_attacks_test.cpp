// Attacks of issue #53 on the commands as a user runs them (the in-process
// ones: tests/unit/reader_attacks_test.cpp).
//
// TerminalOutput: text from a file or a program reaches the user's terminal
// with its control characters escaped (util/terminal_text.hpp): a
// scenario's name `\e]0;owned\a\e[2J` (which retitles and clears a
// terminal) and an external controller that prints the same and fails,
// through `lagrange run`, `compare`, `sweep` (a file planted in its rows
// folder too) and `check-gains`. What each
// prints holds no ESC or BEL byte, and shows the escapes as \xNN.
//
// ViewHostHeader: `lagrange view` answers a request with two Host headers
// (the allowed one first) or `Host: localhost\0.evil.example` with 421, no
// data: before, both got a 200.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "support/child.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/wait.hpp"

namespace lagrange::testing {
namespace {

// The escapes as the commands show them.
const std::string kShownName = "evil\\x1b]0;owned\\x07\\x1b[2J";
const std::string kShownLine = "\\x1b]0;owned\\x07\\x1b[2Jlast words";

// A short Pelican scenario named with the escapes; `controller` its section.
std::string hostileScenario(const std::string& dir, const std::string& controller,
                            const std::string& extra = "") {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/hostile.yaml";
  std::ofstream(path) << R"(name: "evil\e]0;owned\a\e[2J"
duration: 0.5
mode: lockstep
robot: {preset: pelican, gravity: 0.0}
initial_state: {q: [0.2, -0.1], qdot: [0.0, 0.0]}
reference: {type: sine, offset: [0.5, -0.2], amplitude: [0.0, 0.0], frequency: [0.0, 0.0]}
plant: {physics_step: 1.0e-4, publish_rate: 1000}
metrics: {tolerance: 1.0e-3, convergence_deadline: 0.4}
)" << controller << extra;
  return path;
}

// A program from outside that prints the escapes and fails.
const std::string kHostileProgram = R"([sh, -c, "printf '\\033]0;owned\\007\\033[2Jlast words\\n'; exit 3"])";
const std::string kTheorem1 =
    "controller: {type: theorem1, kp: [20, 5], kd: [4, 1], a: [50, 50], b: [50, 50]}\n";

void expectNoRawEscapes(const std::string& output) {
  EXPECT_EQ(output.find('\x1b'), std::string::npos) << "a raw ESC reached the terminal:\n" << output;
  EXPECT_EQ(output.find('\x07'), std::string::npos) << "a raw BEL reached the terminal:\n" << output;
}

TEST(TerminalOutput, RunShowsAScenariosNameAndAFailedProgramsLastLinesEscaped) {
  const std::string dir = freshDir("terminal-run");
  const RunResult failed = runScenario(
      hostileScenario(dir, "controller: {type: external, command: " + kHostileProgram + "}\n"), dir + "/out");
  EXPECT_EQ(failed.exit_code, 1) << failed.output;
  expectNoRawEscapes(failed.output);
  EXPECT_NE(failed.output.find("process 'controller' exited with code 3"), std::string::npos)
      << failed.output;
  EXPECT_NE(failed.output.find("    " + kShownLine), std::string::npos) << failed.output;

  // A run that completes prints its name in the result block.
  const RunResult done =
      runScenario(hostileScenario(dir + "/ok", kTheorem1), dir + "/ok/out", "--mode inproc");
  EXPECT_EQ(done.exit_code, 0) << done.output;
  expectNoRawEscapes(done.output);
  EXPECT_NE(done.output.find("scenario " + kShownName + ": completed"), std::string::npos) << done.output;
}

TEST(TerminalOutput, CompareShowsNamesAndAFailedRowsWordsEscaped) {
  const std::string dir = freshDir("terminal-compare");
  const std::string config = hostileScenario(
      dir, kTheorem1,
      "compare:\n  controllers:\n    theorem1: {}\n    broken: {type: external, command: " + kHostileProgram +
          "}\n");
  const RunResult r = lagrange("compare " + quote(config) + " -o " + quote(dir + "/out"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  expectNoRawEscapes(r.output);
  EXPECT_NE(r.output.find("# Comparison: " + kShownName), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| broken | failed"), std::string::npos) << r.output;
}

// A sweep's failed row, and a file planted in its rows folder whose name
// holds the escapes: `sweep collect` names it escaped.
TEST(TerminalOutput, SweepShowsAFailedRowAndAPlantedFilesNameEscaped) {
  const std::string dir = freshDir("terminal-sweep");
  const std::string config =
      hostileScenario(dir, "controller: {type: external, command: " + kHostileProgram + "}\n");
  std::ofstream(dir + "/sweep.yaml") << "scenario: " << config
                                     << "\naxes:\n  - {key: duration, values: [0.5]}\n";
  const RunResult r = lagrange("sweep " + quote(dir + "/sweep.yaml") + " -o " + quote(dir + "/out") + " -q");
  EXPECT_NE(r.exit_code, 0) << r.output;
  expectNoRawEscapes(r.output);
  EXPECT_NE(r.output.find("row 0 failed: "), std::string::npos) << r.output;

  std::ofstream(dir + "/out/rows/x\x1b]0;owned\x07.jsonl") << "\n";
  const RunResult collect = lagrange("sweep collect " + quote(dir + "/out"));
  EXPECT_EQ(collect.exit_code, 2) << collect.output;
  expectNoRawEscapes(collect.output);
  EXPECT_NE(collect.output.find("/out/rows/x\\x1b]0;owned\\x07.jsonl' is not named as a shard"),
            std::string::npos)
      << collect.output;
}

// An error quoting the scenario file (an unknown key) is printed escaped.
TEST(TerminalOutput, AnErrorQuotingTheScenarioIsEscaped) {
  const std::string dir = freshDir("terminal-error");
  const RunResult r =
      lagrange("check-gains " + quote(hostileScenario(dir, kTheorem1, "\"\\e]0;owned\\a\": 1\n")));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  expectNoRawEscapes(r.output);
  EXPECT_NE(r.output.find("\\x1b]0;owned\\x07"), std::string::npos) << r.output;
}

// One request as raw bytes to 127.0.0.1:port; the answer, until the server closes.
std::string rawRequest(int port, const std::string& bytes) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string answer;
  if (connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
    (void)send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    char buf[4096];
    for (pollfd p{fd, POLLIN, 0}; poll(&p, 1, 5000) > 0;) {
      const ssize_t got = recv(fd, buf, sizeof buf, 0);
      if (got <= 0) break;
      answer.append(buf, static_cast<std::size_t>(got));
    }
  }
  close(fd);
  return answer;
}

TEST(ViewHostHeader, TwoHostHeadersOrANulInTheNameAreRefused) {
  const std::string kNulHost("Host: localhost\0.evil.example\r\n",
                             sizeof "Host: localhost\0.evil.example\r\n" - 1);
  const std::string output = freshDir("view-host") + ".out";
  Child view({kBin + "/lagrange", "view", kGoldenRigidLockstep, "--port", "0"}, output);
  int port = 0;
  waitFor(
      [&] {
        std::smatch m;
        const std::string text = slurp(output);
        if (std::regex_search(text, m, std::regex(R"(http://127\.0\.0\.1:([0-9]+)/)")))
          port = std::stoi(m[1]);
        return port > 0 || !view.running();
      },
      30);
  ASSERT_GT(port, 0) << slurp(output);
  const std::string own = "127.0.0.1:" + std::to_string(port);
  const auto get = [&](const std::string& host_lines) {
    return rawRequest(port, "GET /api/log HTTP/1.1\r\n" + host_lines + "Connection: close\r\n\r\n");
  };
  const std::string fine = get("Host: " + own + "\r\n");
  EXPECT_EQ(fine.rfind("HTTP/1.1 200", 0), 0u) << fine.substr(0, 200);
  for (const std::string& hosts :
       {"Host: " + own + "\r\nHost: evil.example\r\n", "Host: evil.example\r\nHost: " + own + "\r\n",
        "Host: " + own + "\r\nhost: " + own + "\r\n", kNulHost,
        std::string("Host: localhost%00.evil.example\r\n")}) {
    const std::string answer = get(hosts);
    EXPECT_EQ(answer.rfind("HTTP/1.1 421", 0), 0u) << hosts << ": " << answer.substr(0, 300);
    EXPECT_EQ(answer.find("\"frames\""), std::string::npos) << hosts << ": the log was served";
  }
  EXPECT_NE(get("Host: " + own + "\r\nHost: evil.example\r\n").find("the request has 2 Host headers"),
            std::string::npos);
  EXPECT_NE(get(kNulHost).find("holds the byte 0x00 at 9"), std::string::npos);
  view.signal(SIGTERM);
  EXPECT_EQ(view.wait(10), 0) << slurp(output);
}

}  // namespace
}  // namespace lagrange::testing
