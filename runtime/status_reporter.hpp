#pragma once
/// @file
/// STATUS: what every process reports about itself (state, last tick, its
/// channel counters, loop statistics), and the plant's "finished" that ends
/// the reactive processes. Templates on the node so the responders can be
/// driven by a fake node in tests (tests/support/fake_node.hpp); the
/// processes use transport::LcmNode.

#include <cmath>
#include <string>

#include "lagrange/loop_stats_t.hpp"
#include "lagrange/status_t.hpp"
#include "transport/channels.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"
#include "transport/process_state.hpp"

namespace lagrange::runtime {

using State = transport::ProcessState;  ///< what STATUS reports

/// Publishes this process's STATUS with its channel counters.
template <class Node>
class BasicStatusReporter {
 public:
  explicit BasicStatusReporter(Node& node) : node_(node) {}

  void publish(State state, int64_t last_tick, double sim_time, double tracking_error = std::nan(""),
               const std::string& message = "") {
    lagrange::status_t s{};
    s.header = transport::makeHeader(std::max<int64_t>(last_tick, 0), std::max(sim_time, 0.0));
    s.process = node_.processName();
    s.state = transport::toString(state);
    s.last_tick = last_tick;
    s.tracking_error = tracking_error;
    // Without a message of its own, what it last refused as invalid: a
    // stalled plant reads it from here (plant/stall_diagnosis.cpp).
    const std::string invalid = message.empty() ? node_.lastInvalid() : std::string();
    s.message = invalid.empty() ? message : "last refused as invalid: " + invalid;
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

  /// Loop statistics included in every STATUS from now on (realtime mode).
  void setLoopStats(const lagrange::loop_stats_t& loop) { loop_ = loop; }

 private:
  Node& node_;
  lagrange::loop_stats_t loop_{};
};

using StatusReporter = BasicStatusReporter<transport::LcmNode>;

/// Progress of a reactive process: its last completed tick and that tick's sim time.
struct Progress {
  int64_t last_tick = -1;
  double sim_time = 0.0;
};

/// Sets `finished` (which must outlive the node) once the plant reports
/// STATUS "finished".
template <class Node>
void watchPlantFinished(Node& node, bool& finished) {
  node.template subscribe<lagrange::status_t>(
      transport::kStatus, [](const lagrange::status_t& m) { return transport::validate(m); },
      [&finished](const lagrange::status_t& m) {
        if (m.process == "plant" && m.state == transport::toString(State::kFinished)) finished = true;
      });
}

}  // namespace lagrange::runtime
