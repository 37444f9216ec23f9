#include "runtime/process.hpp"

#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>

#include "model/error.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "transport/rate_loop.hpp"

namespace lagrange::runtime {

namespace {
std::atomic<bool> stop_flag{false};
void onStopSignal(int) { stop_flag = true; }
}  // namespace

bool stopRequested() { return stop_flag.load(); }

void StatusReporter::publish(const std::string& state, int64_t last_tick, double sim_time,
                             double tracking_error, const std::string& message) {
  lagrange::status_t s{};
  s.header = transport::makeHeader(std::max<int64_t>(last_tick, 0), std::max(sim_time, 0.0));
  s.process = node_.processName();
  s.state = state;
  s.last_tick = last_tick;
  s.tracking_error = tracking_error;
  s.message = message;
  // Count this STATUS before taking the snapshot so the numbers it reports
  // include itself.
  s.channels = node_.channelStats();
  bool found = false;
  for (auto& c : s.channels)
    if (c.channel == transport::kStatus) {
      c.published++;
      found = true;
    }
  if (!found) {
    lagrange::channel_stats_t c{};
    c.channel = transport::kStatus;
    c.published = 1;
    c.received = c.rejected = 0;
    s.channels.push_back(c);
  }
  s.num_channels = static_cast<int32_t>(s.channels.size());
  s.loop = loop_;
  node_.publish(transport::kStatus, s);
}

void watchPlantFinished(transport::LcmNode& node, bool& finished) {
  node.subscribe<lagrange::status_t>(
      transport::kStatus, [](const auto& m) { return transport::validate(m); },
      [&finished](const lagrange::status_t& m) {
        if (m.process == "plant" && m.state == "finished") finished = true;
      });
}

int serveUntilPlantFinished(transport::LcmNode& node, const Progress& progress,
                            const std::function<void()>& when_idle, double idle_seconds) {
  bool plant_finished = false;
  watchPlantFinished(node, plant_finished);
  StatusReporter status(node);
  status.publish("ready", progress.last_tick, progress.sim_time);
  auto next_status = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  const auto idle_period = std::chrono::duration<double>(idle_seconds);
  int64_t seen_tick = progress.last_tick;
  auto moved_at = std::chrono::steady_clock::now();
  while (!plant_finished && !stopRequested()) {
    if (!node.handle(when_idle ? 5 : 50)) throw std::runtime_error("LCM receive failed");
    if (when_idle) {
      const auto now = std::chrono::steady_clock::now();
      if (progress.last_tick != seen_tick) {
        seen_tick = progress.last_tick;
        moved_at = now;
      } else if (now - moved_at >= idle_period) {
        when_idle();
        moved_at = now;
      }
    }
    if (std::chrono::steady_clock::now() >= next_status) {
      status.publish("running", progress.last_tick, progress.sim_time);
      next_status += std::chrono::milliseconds(500);
    }
  }
  status.publish(plant_finished ? "finished" : "interrupted", progress.last_tick, progress.sim_time);
  return 0;
}

std::string withReceiveBuffer(const std::string& url, int bytes) {
  if (bytes <= 0 || url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size=") != std::string::npos)
    return url;
  return url + (url.find('?') == std::string::npos ? "?" : "&") + "recv_buf_size=" + std::to_string(bytes);
}

int runProcess(const std::string& name, const std::string& description, int argc, char** argv,
               const std::function<void(CLI::App&)>& add_options, const ProcessBody& body,
               int receive_buffer_bytes) {
  CLI::App app{description, "lagrange-" + name};
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
  if (add_options) add_options(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  spdlog::set_pattern("[%H:%M:%S.%e] [" + name + "] [%^%l%$] %v");

  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
  std::signal(SIGPIPE, SIG_IGN);

  try {
    const config::Scenario scenario = config::loadScenario(config_path, overrides);
    // Before LCM starts its receive thread, so that the thread inherits it.
    if (scenario.mode == config::Mode::kRealtime &&
        transport::enterRealtimeScheduling(scenario.realtime.priority) == "other" &&
        scenario.realtime.priority > 0)
      spdlog::warn(
          "SCHED_FIFO priority {} is not allowed here (needs root or CAP_SYS_NICE); running under "
          "the normal scheduler",
          scenario.realtime.priority);
    transport::LcmNode node(name, withReceiveBuffer(url, receive_buffer_bytes), run_id);
    // Each process its own stream of draws, the same in every run with this seed.
    const auto seed_for = [&name](uint64_t seed) {
      for (const unsigned char c : name) seed = (seed ^ c) * 1099511628211ULL;
      return seed;
    };
    if (!scenario.faults.channels.empty()) {
      node.injectFaults(scenario.faults.channels, seed_for(scenario.faults.seed));
      spdlog::info("fault injection on: seed {}", scenario.faults.seed);
    }
    if (const auto it = scenario.faults.receiver_drop.find(name); it != scenario.faults.receiver_drop.end()) {
      node.loseOnReceive(it->second, seed_for(scenario.faults.seed ^ 0x7265636569766572ULL));  // "receiver"
      spdlog::info("{} loses {} of the datagrams it receives (faults.receivers)", name, it->second);
    }
    return body(scenario, node);
  } catch (const config::ConfigError& e) {
    spdlog::error("{}", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    spdlog::error("{}: {}", name, e.what());
    return kExitFailed;
  }
}

}  // namespace lagrange::runtime
