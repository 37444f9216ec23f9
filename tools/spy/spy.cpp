#include "tools/spy/spy.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tools/command_error.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "wiring/netns.hpp"

namespace lagrange::tools {

namespace fs = std::filesystem;

namespace {
constexpr const char* kEndpointFile = "lcm.json";

std::string requireFile(const fs::path& path, const std::string& what_provides_it) {
  if (!fs::exists(path)) throw BadInput(path.string() + " not found; " + what_provides_it);
  return path.string();
}

bool processAlive(long pid) { return fs::exists("/proc/" + std::to_string(pid) + "/ns/net"); }
}  // namespace

void writeEndpoint(const std::string& out_dir, const RunEndpoint& endpoint) {
  nlohmann::json j = {{"lcm_url", endpoint.lcm_url}, {"run_id", endpoint.run_id}, {"netns_pid", nullptr}};
  if (endpoint.netns_pid) j["netns_pid"] = *endpoint.netns_pid;
  if (endpoint.launcher_pid) j["launcher_pid"] = *endpoint.launcher_pid;
  util::writeOutputFile((fs::path(out_dir) / kEndpointFile).string(), j.dump(2) + "\n");
}

RunEndpoint readEndpoint(const std::string& out_dir) {
  const fs::path path = fs::path(out_dir) / kEndpointFile;
  std::ifstream in(path);
  if (!in)
    throw BadInput("no " + path.string() +
                   ": expected the output directory of a `lagrange run` over LCM (inproc runs have no "
                   "LCM traffic)");
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    RunEndpoint e;
    e.lcm_url = j.at("lcm_url").get<std::string>();
    e.run_id = j.value("run_id", int64_t{0});
    if (!j.at("netns_pid").is_null()) e.netns_pid = j.at("netns_pid").get<long>();
    if (j.contains("launcher_pid")) e.launcher_pid = j.at("launcher_pid").get<long>();
    return e;
  } catch (const nlohmann::json::exception& ex) {
    throw BadInput(path.string() + " is not what lagrange run writes (lcm_url, netns_pid): " + ex.what());
  }
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

int runSpy(const SpyOptions& opt) {
  try {
    std::string url = opt.lcm_url;
    if (!opt.run_dir.empty()) {
      const RunEndpoint e = readEndpoint(opt.run_dir);
      if (url.empty()) url = e.lcm_url;
      if (e.netns_pid && !opt.print_only) {
        if (!processAlive(*e.netns_pid))
          throw BadInput("the run in " + opt.run_dir + " has ended (its launcher, pid " +
                         std::to_string(*e.netns_pid) +
                         ", is gone); start lagrange spy while the run is going");
        wiring::joinNetnsOf(*e.netns_pid);
      }
    }
    const std::vector<std::string> cmd = spyCommand(url);
    if (opt.print_only) {
      for (const auto& c : cmd) std::cout << c << (&c == &cmd.back() ? "\n" : " ");
      return kExitOk;
    }
    if (std::getenv("DISPLAY") == nullptr)
      throw BadInput(
          "lcm-spy opens a window and DISPLAY is not set (log in with ssh -X, or use a virtual "
          "display: xvfb-run lagrange spy ...)");
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
