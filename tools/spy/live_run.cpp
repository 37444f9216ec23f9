#include "tools/spy/live_run.hpp"

#include <chrono>
#include <filesystem>
#include <optional>
#include <ostream>
#include <thread>

#include "util/error.hpp"
#include "util/number_text.hpp"
#include "util/terminal_text.hpp"

namespace lagrange::tools {

namespace fs = std::filesystem;

namespace {

std::string startOne(const std::string& dir) { return "lagrange run SCENARIO --mode realtime --out " + dir; }

// How long a refused lcm.json is looked at again: `lagrange run` writes it
// as it starts, and a reader may find it half written.
constexpr double kRefusedGrace = 2.0;
constexpr auto kPoll = std::chrono::milliseconds(200);

}  // namespace

LiveRunProbe probeLiveRun(const std::string& dir) {
  LiveRunProbe p;
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (!fs::exists(st)) return p;  // kMissing
  if (!fs::is_directory(st)) {
    p.state = LiveRunProbe::State::kNotAFolder;
    return p;
  }
  if (!fs::exists(fs::symlink_status(fs::path(dir) / "lcm.json", ec))) {
    p.state = LiveRunProbe::State::kNoEndpoint;
    return p;
  }
  try {
    p.endpoint = readEndpoint(dir);
  } catch (const std::exception& e) {
    p.state = LiveRunProbe::State::kRefused;
    p.problem = e.what();
    return p;
  }
  // A file from before launcher_pid existed cannot say; it is taken as going (as before).
  p.state = p.endpoint.launcher_pid && !launcherAlive(*p.endpoint.launcher_pid) ? LiveRunProbe::State::kEnded
                                                                                : LiveRunProbe::State::kLive;
  return p;
}

std::string notLiveText(const std::string& dir, const LiveRunProbe& p) {
  const std::string expected = "expected the output folder of a running `" + startOne(dir) + "`";
  switch (p.state) {
    case LiveRunProbe::State::kMissing:
      return "the run folder " + dir + " does not exist; " + expected;
    case LiveRunProbe::State::kNotAFolder:
      return dir + " is not a folder; " + expected;
    case LiveRunProbe::State::kNoEndpoint:
      return "no " + (fs::path(dir) / "lcm.json").string() +
             " (a run writes it as it starts; inproc runs have no LCM traffic and write none); " + expected;
    case LiveRunProbe::State::kRefused:
      return p.problem;
    case LiveRunProbe::State::kEnded:
      return "the run in " + dir + " has ended (its launcher, pid " +
             std::to_string(p.endpoint.launcher_pid.value_or(0)) +
             ", is gone); start lagrange spy while the run is going, or before: it waits for one (--wait)";
    case LiveRunProbe::State::kLive:
      break;
  }
  return "";
}

RunEndpoint waitForLiveRun(const std::string& dir, double seconds, std::ostream& say,
                           const std::function<void()>& before_waiting) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  std::optional<Clock::time_point> refused_since;
  bool said = false;
  for (;;) {
    const LiveRunProbe p = probeLiveRun(dir);
    if (p.state == LiveRunProbe::State::kLive) return p.endpoint;
    if (p.state != LiveRunProbe::State::kRefused)
      refused_since.reset();
    else if (!refused_since)
      refused_since = Clock::now();
    const bool refused_for_good = refused_since && since(*refused_since) >= kRefusedGrace;
    if (refused_for_good || p.state == LiveRunProbe::State::kNotAFolder || since(start) >= seconds) {
      std::string why = notLiveText(dir, p);
      if (said && !refused_for_good) why += " (waited " + util::exactText(seconds) + " s: --wait)";
      throw BadInput(why);
    }
    if (!said) {
      before_waiting();
      say << "lagrange spy: waiting for a live run in " << util::terminalSafe(dir)
          << " (start one with: " << util::terminalSafe(startOne(dir)) << "); Ctrl-C stops" << std::endl;
      said = true;
    }
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace lagrange::tools
