#pragma once
/// @file
/// The lockstep rule of a reactive process (controller, actuator): one output
/// per input tick. A repeated tick (the plant re-sending after a timeout, or
/// re-sending a tick the logger has not confirmed) is answered with the
/// output sent for it, kept for the last `history` ticks, so no core ever
/// steps twice on one sample; a tick older than that is ignored. `compute`
/// may decline (empty result) when another input of the tick is still
/// missing; the tick is then answered when the plant re-sends it.

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "runtime/process.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"

namespace lagrange::runtime {

/// Returns the cached output (the answer to the newest tick), for re-sending.
template <class In, class Out>
std::shared_ptr<const std::optional<Out>> respondPerTick(
    transport::LcmNode& node, const std::string& in_channel, const std::string& out_channel, int joints,
    Progress& progress, int history, std::function<std::optional<Out>(const In&)> compute) {
  auto cached = std::make_shared<std::optional<Out>>();
  auto sent = std::make_shared<std::map<int64_t, Out>>();  // the last `history` answers, by tick
  node.subscribe<In>(
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

}  // namespace lagrange::runtime
