#pragma once
/// @file
/// Signalling a process of a running scenario from a test: find it by name
/// and output directory, send the signal once the run is under way.

#include <signal.h>
#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {

/// The pid of a process whose argv[0] ends with `name` and whose command line
/// mentions `needle`, or -1.
inline pid_t findProcess(const std::string& name, const std::string& needle) {
  namespace fs = std::filesystem;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "cmdline");
    std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string argv0 = cmdline.substr(0, cmdline.find('\0'));
    if (argv0.size() >= name.size() && argv0.compare(argv0.size() - name.size(), name.size(), name) == 0 &&
        cmdline.find(needle) != std::string::npos)
      return static_cast<pid_t>(std::stol(pid));
  }
  return -1;
}

struct SignalledRun {
  RunResult result;
  bool signalled = false;
};

/// Runs `config` into `dir` with `args` and sends `sig` to `process` once
/// `ready(run.lcm)` holds (the run is far enough); returns when the run ends.
inline SignalledRun signalWhen(const std::string& dir, const std::string& config, const std::string& process,
                               int sig, const std::string& args,
                               const std::function<bool(const std::filesystem::path&)>& ready) {
  namespace fs = std::filesystem;
  SignalledRun out;
  std::atomic<bool> done{false};
  std::thread runner([&] {
    out.result = runScenario(config, dir, args);
    done = true;
  });
  const fs::path log = fs::path(dir) / "run.lcm";
  // Polls until the run is far enough or over: a sanitizer build runs the
  // Panda several times slower than 30 s would allow (the cap is only there
  // so a run that never ends cannot hold the test forever).
  for (int i = 0; i < 12000 && !out.signalled && !done; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
    if (!fs::exists(log) || !ready(log)) continue;
    const pid_t pid = findProcess(process, dir);
    out.signalled = pid > 0 && kill(pid, sig) == 0;
  }
  runner.join();
  return out;
}

/// signalWhen, once run.lcm holds `log_bytes` (the run is under way).
inline SignalledRun signalMidRun(const std::string& dir, const std::string& config,
                                 const std::string& process, int sig,
                                 const std::string& args = "--set duration=600 -q",
                                 std::uintmax_t log_bytes = 100000) {
  return signalWhen(dir, config, process, sig, args, [log_bytes](const std::filesystem::path& log) {
    return std::filesystem::file_size(log) >= log_bytes;
  });
}

/// signalWhen, once run.lcm holds a PLANT_TRUTH sample of simulated time
/// `sim_time` or later: a point of the run in its own time, which the log's
/// size is not (how many bytes a simulated second takes varies with the
/// retransmissions and skips of a loaded machine).
inline SignalledRun signalAtSimTime(const std::string& dir, const std::string& config,
                                    const std::string& process, int sig, const std::string& args,
                                    double sim_time) {
  return signalWhen(dir, config, process, sig, args, [sim_time](const std::filesystem::path& log) {
    try {  // the log is being written: a half-written last event is left for the next poll
      const std::vector<TruthSample> truth = readTruth(log.string());
      return !truth.empty() && truth.back().t >= sim_time;
    } catch (const std::exception&) {
      return false;
    }
  });
}

}  // namespace lagrange::testing
