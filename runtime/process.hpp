#pragma once
/// @file
/// What every lagrange process shares: the command line (--config,
/// --lcm-url), stop signals, STATUS reporting and the top-level error policy
/// (a user error prints what was wrong and what was expected, then exits 2;
/// a runtime failure exits 1). Process mains stay thin by building on it.

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <string>

#include "config/scenario.hpp"
#include "lagrange/loop_stats_t.hpp"
#include "transport/lcm_node.hpp"

namespace lagrange::runtime {

/// Default LCM URL: LCM's own default group and port, TTL 0 (never leaves the host).
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

/// True once SIGINT or SIGTERM arrived.
bool stopRequested();

/// Publishes this process's STATUS with its channel counters.
class StatusReporter {
 public:
  explicit StatusReporter(transport::LcmNode& node) : node_(node) {}
  void publish(const std::string& state, int64_t last_tick, double sim_time,
               double tracking_error = std::nan(""), const std::string& message = "");

  /// Loop statistics included in every STATUS from now on (realtime mode).
  void setLoopStats(const lagrange::loop_stats_t& loop) { loop_ = loop; }

 private:
  transport::LcmNode& node_;
  lagrange::loop_stats_t loop_{};
};

/// Progress of a reactive process: its last completed tick and that tick's sim time.
struct Progress {
  int64_t last_tick = -1;
  double sim_time = 0.0;
};

/// Sets `finished` (which must outlive the node) once the plant reports
/// STATUS "finished".
void watchPlantFinished(transport::LcmNode& node, bool& finished);

/// The loop of a process that only reacts to messages (controller, actuator):
/// publishes STATUS "ready", handles messages with periodic "running" reports
/// until the plant reports "finished" or a stop signal arrives, then
/// publishes the final STATUS. Returns the exit code (0).
/// `when_idle`, if given, runs whenever `progress` has not moved for
/// `idle_seconds` (the actuator re-sends its last state: nobody else can
/// re-request it).
int serveUntilPlantFinished(transport::LcmNode& node, const Progress& progress,
                            const std::function<void()>& when_idle = {}, double idle_seconds = 0.0);

/// The body of a process: gets the validated scenario and a connected node;
/// returns the exit code.
using ProcessBody = std::function<int(const config::Scenario&, transport::LcmNode&)>;

/// Parses the common options (plus those `add_options` adds), installs the
/// signal handlers, loads the scenario, connects LCM and runs `body`,
/// translating exceptions into messages and exit codes. A positive
/// receive_buffer_bytes asks the kernel for that UDP receive buffer
/// (LCM's recv_buf_size; capped by net.core.rmem_max, and LCM warns then).
int runProcess(const std::string& name, const std::string& description, int argc, char** argv,
               const std::function<void(CLI::App&)>& add_options, const ProcessBody& body,
               int receive_buffer_bytes = 0);

/// The LCM URL with recv_buf_size=bytes added (udpm URLs without one only).
std::string withReceiveBuffer(const std::string& url, int bytes);

}  // namespace lagrange::runtime
