#pragma once
/// @file
/// Running the `lagrange` front end from integration tests: a fresh output
/// directory per run, the command's exit code and its combined output.

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

namespace lagrange::testing {

/// The folder of the programs the tests run: this build's, or the one
/// LAGRANGE_TEST_PROGRAMS names. The sanitizer pass runs the normal build's
/// integration tests against its instrumented programs that way
/// (scripts/test_sanitizers.sh): the programs are what it checks, and the
/// test program's own build under the sanitizers was 3 minutes of CI.
inline std::string testProgramsDir() {
  const char* dir = std::getenv("LAGRANGE_TEST_PROGRAMS");
  return dir != nullptr && *dir != '\0' ? std::string(dir) : std::string(LAGRANGE_BIN_DIR);
}
inline const std::string kBin = testProgramsDir();

struct RunResult {
  int exit_code = -1;
  std::string output;
};

inline std::string freshDir(const std::string& tag) {
  static std::mt19937_64 rng(std::random_device{}());
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("lagrange-test-" + tag + "-" + std::to_string(rng() % 1000000000));
  std::filesystem::remove_all(dir);
  return dir.string();
}

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

/// A shell command's exit code and combined output.
inline RunResult shell(const std::string& command) {
  RunResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buf[4096];
  while (size_t got = fread(buf, 1, sizeof buf, pipe)) r.output.append(buf, got);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline RunResult lagrange(const std::string& args) { return shell(kBin + "/lagrange " + args); }

inline RunResult runScenario(const std::string& config, const std::string& out,
                             const std::string& extra = "") {
  return lagrange("run " + quote(config) + " --out " + quote(out) + " " + extra);
}

}  // namespace lagrange::testing
