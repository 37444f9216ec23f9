#pragma once
/// @file
/// The lockstep rule of a reactive process (controller, actuator): one output
/// per input tick. A repeated tick (the plant re-sending after a timeout, or
/// re-sending a tick the logger has not confirmed) is answered with the
/// output sent for it, kept for the last `history` ticks, so no core ever
/// steps twice on one sample; a tick older than that is ignored. `compute`
/// may decline (empty result) when another input of the tick is still
/// missing; the tick is then answered when the plant re-sends it.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "runtime/process.hpp"
#include "runtime/status_reporter.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"
#include "util/error.hpp"

namespace lagrange::runtime {

/// Returns the cached output (the answer to the newest tick), for re-sending.
/// `Node` is transport::LcmNode in the processes (a fake node in tests).
template <class In, class Out, class Node>
std::shared_ptr<const std::optional<Out>> respondPerTick(
    Node& node, const std::string& in_channel, const std::string& out_channel, int joints, Progress& progress,
    int history, std::function<std::optional<Out>(const In&)> compute) {
  auto cached = std::make_shared<std::optional<Out>>();
  auto sent = std::make_shared<std::map<int64_t, Out>>();  // the last `history` answers, by tick
  node.template subscribe<In>(
      in_channel, [joints](const In& m) { return transport::validate(m, joints); },
      [&node, &progress, out_channel, compute, cached, sent, history](const In& m) {
        if (m.header.tick <= progress.last_tick) {
          if (const auto it = sent->find(m.header.tick); it != sent->end())
            node.publish(out_channel, it->second);
          return;
        }
        std::optional<Out> out = compute(m);
        if (!out) return;  // not ready: the sender re-sends this tick
        *cached = std::move(out);
        node.publish(out_channel, **cached);
        progress = {m.header.tick, m.header.sim_time};
        sent->emplace(m.header.tick, **cached);
        while (static_cast<int>(sent->size()) > history) sent->erase(sent->begin());
      });
  return cached;
}

/// The loop of a process that only reacts to messages (controller, actuator):
/// publishes STATUS "ready", handles messages with periodic "running" reports
/// until the plant reports "finished" or a stop signal arrives, then
/// publishes the final STATUS. Returns the exit code (0).
/// `when_idle`, if given, runs whenever `progress` has not moved for
/// `idle_seconds` (the actuator re-sends its last state: nobody else can
/// re-request it).
template <class Node>
int serveUntilPlantFinished(Node& node, const Progress& progress, const std::function<void()>& when_idle = {},
                            double idle_seconds = 0.0) {
  using Clock = std::chrono::steady_clock;
  bool plant_finished = false;
  watchPlantFinished(node, plant_finished);
  BasicStatusReporter<Node> status(node);
  status.publish(State::kReady, progress.last_tick, progress.sim_time);
  auto next_status = Clock::now() + std::chrono::milliseconds(500);
  const auto idle_period = std::chrono::duration<double>(idle_seconds);
  int64_t seen_tick = progress.last_tick;
  auto moved_at = Clock::now();
  while (!plant_finished && !stopRequested()) {
    if (!node.handle(when_idle ? 5 : 50)) throw lagrange::RuntimeFault("LCM receive failed");
    if (when_idle) {
      const auto now = Clock::now();
      if (progress.last_tick != seen_tick) {
        seen_tick = progress.last_tick;
        moved_at = now;
      } else if (now - moved_at >= idle_period) {
        when_idle();
        moved_at = now;
      }
    }
    if (Clock::now() >= next_status) {
      status.publish(State::kRunning, progress.last_tick, progress.sim_time);
      next_status += std::chrono::milliseconds(500);
    }
  }
  status.publish(plant_finished ? State::kFinished : State::kInterrupted, progress.last_tick,
                 progress.sim_time);
  return 0;
}

}  // namespace lagrange::runtime
