#include "runtime/process.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <optional>

#include "config/work_bounds.hpp"
#include "runtime/key_file.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "transport/rate_loop.hpp"
#include "util/error.hpp"
#include "util/text_wrap.hpp"

namespace lagrange::runtime {

namespace {
std::atomic<bool> stop_flag{false};
void onStopSignal(int) { stop_flag = true; }
std::atomic<bool> resumed_flag{false};
void onContinueSignal(int) { resumed_flag = true; }
}  // namespace

bool stopRequested() { return stop_flag.load(); }

int niceValue() {
  errno = 0;
  const int nice = getpriority(PRIO_PROCESS, 0);
  return errno == 0 ? nice : 0;
}

void niceAtLeast(int nice, const std::string& key) {
  if (nice <= niceValue()) return;
  if (setpriority(PRIO_PROCESS, 0, nice) != 0) {
    const int error = errno;  // before niceValue(), which resets errno
    spdlog::warn(fmt::format("{}: cannot set nice {}: {}; running at nice {}", key, nice,
                             std::strerror(error), niceValue()));
  }
}

bool takeResumeNotice() { return resumed_flag.exchange(false); }

std::string withReceiveBuffer(const std::string& url, int bytes) {
  if (bytes <= 0 || url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size=") != std::string::npos)
    return url;
  return url + (url.find('?') == std::string::npos ? "?" : "&") + "recv_buf_size=" + std::to_string(bytes);
}

int runProcess(const std::string& name, const std::string& description, int argc, char** argv,
               const std::vector<ProcessOption>& options, const ProcessPrepare& prepare,
               const ProcessBody& body, int receive_buffer_bytes) {
  CLI::App app{description, "lagrange-" + name};
  // Started by `lagrange run`; by hand, as docs/deployment.md shows, every
  // process of a run takes the same four options.
  app.footer(util::helpFooter(
      "One process of a run, normally started by `lagrange run`, which gives it the run's resolved "
      "scenario, LCM URL, run id and key. Started by hand (docs/deployment.md: the processes of one "
      "run on several hosts), every process of the run takes the same --config, --lcm-url, --run-id "
      "and --key-file (a key file from `lagrange keygen`); the example's files are a run's resolved "
      "scenario and such a key.",
      {"lagrange-" + name +
       " --config runs/rigid_2dof/config.resolved.yaml --lcm-url 'udpm://239.255.76.67:7667?ttl=0' --run-id "
       "7 --key-file runs/shared.key" +
       (name == "logger" ? " --out runs/by_hand" : "")}));
  std::string config_path;
  std::string url = kDefaultLcmUrl;
  std::vector<std::string> overrides;
  int64_t run_id = 0;
  app.add_option("--run-id", run_id,
                 "The run's identity: stamped on every message, required of every message received "
                 "(0: accept any run)")
      ->capture_default_str();
  app.add_option("-c,--config", config_path, "Scenario YAML file (e.g. config.resolved.yaml)")->required();
  app.add_option("--lcm-url", url, "LCM URL shared by every process of the run")->capture_default_str();
  app.add_option("--set", overrides, "Override a config key, key=value (YAML value); repeatable");
  std::string key_file;
  app.add_option("--key-file", key_file,
                 "The run's secret key (64 hex digits, mode 600): every message is signed with it and "
                 "must carry its MAC (without: neither signed nor checked)");
  for (const ProcessOption& o : options) {
    CLI::Option* option = std::visit(
        [&](auto* target) -> CLI::Option* {
          if constexpr (std::is_same_v<decltype(target), bool*>)
            return app.add_flag(o.names, *target, o.help);
          else
            return app.add_option(o.names, *target, o.help);
        },
        o.target);
    if (o.show_default) option->capture_default_str();
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  spdlog::set_pattern("[%H:%M:%S.%e] [" + name + "] [%^%l%$] %v");

  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
  std::signal(SIGCONT, onContinueSignal);
  std::signal(SIGPIPE, SIG_IGN);

  try {
    const config::Scenario scenario = config::loadScenario(config_path, overrides);
    if (prepare) prepare(scenario);
    // Before LCM starts its receive thread, so that the thread inherits it.
    // CPUs first: the policy, the memory and every thread stay where they are put.
    if (scenario.mode == config::Mode::kRealtime)
      if (const auto it = scenario.realtime.cpus.find(name); it != scenario.realtime.cpus.end())
        transport::pinToCpus(it->second, "realtime.cpus." + name);
    if (scenario.mode == config::Mode::kRealtime &&
        transport::enterRealtimeScheduling(scenario.realtime.priority) == "other" &&
        scenario.realtime.priority > 0)
      spdlog::warn(fmt::format(
          "SCHED_FIFO priority {} is not allowed here (needs root or CAP_SYS_NICE); running under "
          "the normal scheduler",
          scenario.realtime.priority));
    // Read before anything starts: a bad key file is bad input (exit 2).
    const std::optional<transport::MessageKey> key =
        key_file.empty() ? std::nullopt : std::optional(readKeyFile(key_file));
    transport::LcmNode node(name, withReceiveBuffer(url, receive_buffer_bytes), run_id);
    // No per-tick datagram larger than this run's largest honest one is decoded
    // (the controller's cascade reports at most the highest order's stages).
    node.boundMessages(
        {scenario.dof(), scenario.actuator.order, scenario.torqueStepsPerTick(), config::kMaxActuatorOrder});
    if (key)
      node.authenticate(*key);
    else
      spdlog::warn(
          "no --key-file: messages are neither signed nor checked, so anyone on the LCM group can forge "
          "them (lagrange run always gives one)");
    // Each process its own stream of draws, the same in every run with this seed.
    const auto seed_for = [&name](uint64_t seed) {
      for (const unsigned char c : name) seed = (seed ^ c) * 1099511628211ULL;
      return seed;
    };
    if (!scenario.faults.channels.empty()) {
      node.injectFaults(scenario.faults.channels, seed_for(scenario.faults.seed));
      spdlog::info(fmt::format("fault injection on: seed {}", scenario.faults.seed));
    }
    if (const auto it = scenario.faults.receiver_drop.find(name); it != scenario.faults.receiver_drop.end()) {
      node.loseOnReceive(it->second, seed_for(scenario.faults.seed ^ 0x7265636569766572ULL));  // "receiver"
      spdlog::info(
          fmt::format("{} loses {} of the datagrams it receives (faults.receivers)", name, it->second));
    }
    return body(scenario, node);
  } catch (const std::exception& e) {
    // Bad input names its key or file itself; a fault is told with the process's name.
    const ExitCode code = exitCodeOf(e);
    if (code == kExitBadInput)
      spdlog::error(fmt::format("{}", e.what()));
    else
      spdlog::error(fmt::format("{}: {}", name, e.what()));
    return code;
  }
}

}  // namespace lagrange::runtime
