#include "tools/spy/spy.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "tools/command_error.hpp"
#include "tools/spy/live_run.hpp"
#include "util/error.hpp"
#include "util/input_file.hpp"
#include "util/output_file.hpp"
#include "util/terminal_text.hpp"
#include "wiring/netns.hpp"

namespace lagrange::tools {

namespace fs = std::filesystem;

namespace {
constexpr const char* kEndpointFile = "lcm.json";

std::string requireFile(const fs::path& path, const std::string& what_provides_it) {
  if (!fs::exists(path)) throw BadInput(path.string() + " not found; " + what_provides_it);
  return path.string();
}

}  // namespace

void writeEndpoint(const std::string& out_dir, const RunEndpoint& endpoint) {
  nlohmann::json j = {{"lcm_url", endpoint.lcm_url}, {"run_id", endpoint.run_id}, {"netns_pid", nullptr}};
  if (endpoint.netns_pid) j["netns_pid"] = *endpoint.netns_pid;
  if (endpoint.launcher_pid) j["launcher_pid"] = *endpoint.launcher_pid;
  util::writeOutputFile((fs::path(out_dir) / kEndpointFile).string(), j.dump(2) + "\n");
}

namespace {

// A decimal number of 1 to `digits` digits without a leading zero, at most
// `max`, at text[at..); advances `at` past it. False if there is none.
bool decimal(const std::string& text, std::size_t& at, unsigned max, std::size_t digits, unsigned& value) {
  std::size_t end = at;
  while (end < text.size() && end - at < digits + 1 && text[end] >= '0' && text[end] <= '9') ++end;
  const std::size_t n = end - at;
  if (n == 0 || n > digits || (n > 1 && text[at] == '0')) return false;
  value = 0;
  for (std::size_t i = at; i < end; ++i) value = value * 10 + static_cast<unsigned>(text[i] - '0');
  if (value > max) return false;
  at = end;
  return true;
}

// The JSON value of a pid: a positive integer, or null where `nullable`.
std::optional<long> pidField(const nlohmann::json& j, const char* key, bool nullable,
                             const std::string& file) {
  const nlohmann::json& v = j.at(key);
  if (nullable && v.is_null()) return std::nullopt;
  if (!v.is_number_integer() || v.get<long long>() <= 0 || v.get<long long>() > 4194304)
    throw BadInput(file + ": " + key + " is " + util::terminalSafe(v.dump().substr(0, 80)) +
                   "; expected the pid `lagrange run` writes (an integer 1 to 4194304" +
                   (nullable ? ", or null" : "") + "). A run folder is read as data, never followed");
  return v.get<long>();
}

}  // namespace

std::string runUrlProblem(const std::string& url) {
  const std::string expected =
      "expected the URL `lagrange run` writes, udpm://A.B.C.D:PORT?ttl=N (a multicast IPv4 address "
      "224.0.0.0 to 239.255.255.255, a port 1 to 65535, at most the option ttl=0 to 255, nothing else)";
  const std::string scheme = "udpm://";
  if (url.compare(0, scheme.size(), scheme) != 0) return "it is not a udpm:// URL; " + expected;
  std::size_t at = scheme.size();
  unsigned octet = 0;
  for (int i = 0; i < 4; ++i) {
    if (i > 0 && (at >= url.size() || url[at++] != '.'))
      return "its address is not four decimal numbers joined by dots; " + expected;
    if (!decimal(url, at, 255, 3, octet))
      return "its address is not four decimal numbers 0 to 255 joined by dots; " + expected;
    if (i == 0 && (octet < 224 || octet > 239))
      return "its address is not a multicast one (224 to 239 first); " + expected;
  }
  unsigned port = 0;
  if (at >= url.size() || url[at++] != ':' || !decimal(url, at, 65535, 5, port) || port == 0)
    return "it has no port 1 to 65535 after its address; " + expected;
  if (at == url.size()) return "";
  const std::string ttl = "?ttl=";
  unsigned hops = 0;
  if (url.compare(at, ttl.size(), ttl) != 0) return "it has more after its port than ?ttl=N; " + expected;
  at += ttl.size();
  if (!decimal(url, at, 255, 3, hops)) return "its ttl is not a number 0 to 255; " + expected;
  if (at != url.size()) return "it has more after its ttl; " + expected;
  return "";
}

bool launcherAlive(long pid) {
  if (pid <= 0) return false;
  if (kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM) return false;
  std::ifstream in("/proc/" + std::to_string(pid) + "/cmdline");
  std::string argv0;
  std::getline(in, argv0, '\0');
  return fs::path(argv0).filename() == "lagrange";
}

RunEndpoint readEndpoint(const std::string& out_dir) {
  const fs::path path = fs::path(out_dir) / kEndpointFile;
  const std::string file = path.string();
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec)))
    throw BadInput("no " + file +
                   ": expected the output directory of a `lagrange run` over LCM (inproc runs have no "
                   "LCM traffic)");
  // Opened without blocking and looked at before a byte is read: a FIFO or
  // /dev/zero in a run folder is refused, not waited on or read for ever.
  const util::InputFile input = util::InputFile::open(file, "the lcm.json `lagrange run` writes");
  if (!input.ok()) throw BadInput(input.error());
  constexpr long long kMaxBytes = 64 * 1024;
  if (input.size() > kMaxBytes)
    throw BadInput(file + " holds " + std::to_string(input.size()) +
                   " bytes; expected the lcm.json `lagrange run` writes (a few lines, at most 64 KiB)");
  std::string text;
  char buf[4096];
  for (ssize_t got; text.size() <= static_cast<std::size_t>(kMaxBytes) &&
                    ((got = read(input.fd(), buf, sizeof buf)) > 0 || (got < 0 && errno == EINTR));)
    if (got > 0) text.append(buf, static_cast<std::size_t>(got));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& ex) {
    throw BadInput(file + " is not what lagrange run writes (lcm_url, netns_pid): " + ex.what());
  }
  if (!j.is_object() || !j.contains("lcm_url") || !j.contains("netns_pid"))
    throw BadInput(file +
                   " is not what lagrange run writes (lcm_url, netns_pid): expected a JSON object with "
                   "lcm_url, run_id, netns_pid and launcher_pid");
  for (const auto& [key, value] : j.items())
    if (key != "lcm_url" && key != "run_id" && key != "netns_pid" && key != "launcher_pid")
      throw BadInput(file + " is not what lagrange run writes: it has the field " +
                     util::terminalSafe(key.substr(0, 80)) +
                     "; expected only lcm_url, run_id, netns_pid and launcher_pid");
  RunEndpoint e;
  if (!j["lcm_url"].is_string())
    throw BadInput(file + " is not what lagrange run writes (lcm_url, netns_pid): lcm_url is not a string");
  e.lcm_url = j["lcm_url"].get<std::string>();
  if (const std::string why = runUrlProblem(e.lcm_url); !why.empty())
    throw BadInput(file + ": lcm_url '" + util::terminalSafe(e.lcm_url.substr(0, 200)) +
                   (e.lcm_url.size() > 200 ? "...'" : "'") + " is refused: " + why +
                   ". A run folder is read as data, never followed; to watch that URL anyway, give it "
                   "yourself: --lcm-url URL, without the folder");
  if (j.contains("run_id")) {
    if (!j["run_id"].is_number_integer())
      throw BadInput(file + ": run_id is not an integer; expected the run id `lagrange run` writes");
    e.run_id = j["run_id"].get<int64_t>();
  }
  e.netns_pid = pidField(j, "netns_pid", true, file);
  if (j.contains("launcher_pid")) e.launcher_pid = pidField(j, "launcher_pid", false, file);
  // The launcher takes the namespace from itself: a folder naming another
  // process's would have spy and view join that process's namespaces.
  if (e.netns_pid && e.launcher_pid && *e.netns_pid != *e.launcher_pid)
    throw BadInput(file + ": netns_pid " + std::to_string(*e.netns_pid) + " is not the launcher_pid " +
                   std::to_string(*e.launcher_pid) +
                   "; expected the launcher's own pid or null, as `lagrange run` writes. A run folder is "
                   "read as data, never followed");
  return e;
}

std::vector<std::string> spyCommand(const std::string& lcm_url) {
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe").parent_path();
  const std::string types = requireFile(exe_dir.parent_path() / "share/java/lagrange_lcmtypes.jar",
                                        "build the project with Java (bash scripts/build.sh)");
  const std::string lcm = requireFile("/usr/share/java/lcm.jar", "install Debian's liblcm-java");
  const std::string chart = requireFile("/usr/share/java/jchart2d.jar", "install Debian's libjchart2d-java");
  std::vector<std::string> cmd = {"java", "-Djava.net.preferIPv4Stack=true", "-Xmx256m",
                                  "-cp",  lcm + ":" + chart + ":" + types,   "lcm.spy.Spy"};
  if (!lcm_url.empty()) cmd.push_back("--lcm-url=" + lcm_url);
  return cmd;
}

namespace {
const char* const kNoDisplay =
    "lcm-spy opens a window and DISPLAY is not set (log in with ssh -X, or use a virtual display: xvfb-run "
    "lagrange spy ...)";

// The run in `dir`: printing the command takes lcm.json as it is (a run
// ended too); lcm-spy itself waits up to `seconds` for a run to be going.
RunEndpoint runIn(const std::string& dir, bool print_only, double seconds) {
  if (!print_only)
    return waitForLiveRun(dir, seconds, std::cerr, [] {
      if (std::getenv("DISPLAY") == nullptr)
        throw BadInput(kNoDisplay);  // said before a long wait, not after
    });
  const LiveRunProbe p = probeLiveRun(dir);
  if (p.state != LiveRunProbe::State::kLive && p.state != LiveRunProbe::State::kEnded)
    throw BadInput(notLiveText(dir, p));
  return p.endpoint;
}
}  // namespace

int runSpy(const SpyOptions& opt) {
  try {
    std::string url = opt.lcm_url;
    if (!opt.run_dir.empty()) {
      const RunEndpoint e = runIn(opt.run_dir, opt.print_only, opt.wait_seconds);
      if (url.empty()) url = e.lcm_url;
      // Only the namespace of a live launcher (readEndpoint: netns_pid is
      // the launcher's): a file written before launcher_pid existed names
      // a run long ended.
      if (e.netns_pid && !opt.print_only) {
        if (!e.launcher_pid || !launcherAlive(*e.launcher_pid))
          throw BadInput("the run in " + opt.run_dir + " has ended (its launcher, pid " +
                         std::to_string(e.launcher_pid.value_or(*e.netns_pid)) +
                         ", is gone); start lagrange spy while the run is going");
        wiring::joinNetnsOf(*e.netns_pid);
      }
    }
    const std::vector<std::string> cmd = spyCommand(url);
    if (opt.print_only) {
      for (const auto& c : cmd) std::cout << c << (&c == &cmd.back() ? "\n" : " ");
      return kExitOk;
    }
    if (std::getenv("DISPLAY") == nullptr) throw BadInput(kNoDisplay);
    std::vector<char*> argv;
    for (const auto& c : cmd) argv.push_back(const_cast<char*>(c.c_str()));
    argv.push_back(nullptr);
    execvp("java", argv.data());
    throw BadInput(std::string("cannot run java: ") + std::strerror(errno) +
                   " (install Debian's default-jre)");
  } catch (const std::exception& e) {
    return failWith("lagrange spy", e);
  }
}

}  // namespace lagrange::tools
