// The bad-configuration corpus (tests/data/bad_configs/*.yaml): each file
// says on its second line, "# expect: ...", the error `lagrange run` must
// print. Every one is refused with exit 2 and that message, and no process
// is started: the output directory is never even created.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "support/configs.hpp"
#include "support/launch.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;
TEST(BadConfigCorpus, EveryFileIsRefusedWithItsMessageBeforeAnythingStarts) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kBadConfigs)) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    SCOPED_TRACE(entry.path().filename().string());
    const std::string expected = expectedMessageOf(entry.path());
    ASSERT_FALSE(expected.empty()) << "no '# expect: ' on the second line";
    const std::string out = freshDir("badconfig");
    const RunResult r = runScenario(entry.path().string(), out, "-q");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("lagrange run: config: " + entry.path().string() + ": " + expected),
              std::string::npos)
        << "expected: " << expected << "\ngot: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << "the output directory was created: something started";
  }
  EXPECT_GE(files, 30);
}

// Bad options are refused the same way: an output directory that cannot be
// created, an override that does not fit the scenario.
TEST(BadConfigCorpus, UnwritableOutputAndBadOverridesAreRefused) {
  const std::string config = std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml";
  const std::string file = freshDir("afile");
  std::ofstream(file) << "a file, not a directory\n";
  for (const std::string& out : {std::string("/proc/lagrange-cannot-be-here"), file + "/sub"}) {
    const RunResult r = runScenario(config, out, "-q");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    // The system's reason in brackets between the two.
    EXPECT_NE(r.output.find("output directory '" + out + "' cannot be created or written ("),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("); expected a writable directory"), std::string::npos) << r.output;
  }
  const std::string out = freshDir("badset");
  const RunResult r = runScenario(config, out, "-q --set controller.kp=[1,2,3]");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("controller.kp: expected a list of 2 positive numbers"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  const RunResult unknown = runScenario(config, out, "-q --set controller.gain=3");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("controller.gain: unknown key"), std::string::npos) << unknown.output;
  EXPECT_FALSE(fs::exists(out));
}

// What is not a scenario file is named as such, without being read: a
// directory, a device that never ends, a FIFO nobody writes to (which would
// block a reader for ever), a file too large to be a scenario.
TEST(BadConfigFile, NonRegularAndLargeFilesAreRefusedWithoutBeingRead) {
  const std::string dir = freshDir("notafile");
  fs::create_directories(dir);
  const std::string fifo = dir + "/pipe.yaml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string big = dir + "/big.yaml";
  std::ofstream(big) << "# " << std::string(2 << 20, 'x') << "\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {dir, "'" + dir + "' is a directory; expected a YAML scenario file (a regular file)"},
      {"/dev/zero", "'/dev/zero' is a character device; expected a YAML scenario file (a regular file)"},
      {fifo, "'" + fifo + "' is a FIFO (named pipe); expected a YAML scenario file (a regular file)"},
      {big, "'" + big + "' is larger than 2 MiB; expected a YAML scenario file of at most 1 MiB"}};
  for (const auto& [config, message] : cases) {
    SCOPED_TRACE(config);
    const std::string out = freshDir("notafile-out");
    const auto start = std::chrono::steady_clock::now();
    const RunResult r = runScenario(config, out, "-q");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("lagrange run: config: " + message), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "the output directory was created: something started";
    const RunResult check = lagrange("check-gains " + quote(config));
    EXPECT_EQ(check.exit_code, 2) << check.output;
    EXPECT_NE(check.output.find("lagrange check-gains: config: " + message), std::string::npos)
        << check.output;
  }
  fs::remove_all(dir);
}

// A chain of `links` equal links, theorem1 gains on every joint.
std::string chainConfig(int links) {
  const std::string path = freshDir("chain" + std::to_string(links)) + ".yaml";
  std::ofstream out(path);
  out << "name: chain\nduration: 1.0\nrobot:\n  links:\n";
  for (int i = 0; i < links; ++i) out << "    - {length: 0.1, com: 0.05, mass: 1.0, inertia: 0.001}\n";
  out << "initial_state:\n  q: [0.1";
  for (int i = 1; i < links; ++i) out << ", 0.0";
  out << "]\nreference: {type: sine, offset: 0.0, amplitude: 0.1, frequency: 1.0}\n"
         "controller: {type: theorem1, kp: 10.0, kd: 1.0, a: 50.0, b: 50.0}\n";
  return path;
}

// The gain check of a long chain (check-gains, and the launcher's check of
// eq. (12) before a run) takes seconds at the joint bound, and a chain past it
// is refused at once with the bound (50 links took 40 s and 6 GB, past 100 aborted).
TEST(BadConfigFile, TheGainCheckOfTheLongestChainTakesSecondsAndALongerOneIsRefused) {
  const std::string longest = chainConfig(16);
  const auto start = std::chrono::steady_clock::now();
  const RunResult check = lagrange("check-gains --no-simulation " + quote(longest));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 60.0) << check.output;
  EXPECT_TRUE(check.exit_code == 0 || check.exit_code == 1) << check.output;
  EXPECT_NE(check.output.find("k_c = "), std::string::npos) << check.output;
  EXPECT_NE(check.output.find("linearised check"), std::string::npos) << check.output;

  const std::string longer = chainConfig(17);
  const RunResult refused = lagrange("check-gains " + quote(longer));
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("robot.links: a chain of 17 links; at most 16 are allowed"),
            std::string::npos)
      << refused.output;
  const std::string out = freshDir("chain17-out");
  const RunResult run = runScenario(longer, out, "-q");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_FALSE(fs::exists(out));
  fs::remove(longest);
  fs::remove(longer);
}

}  // namespace
}  // namespace lagrange::testing
