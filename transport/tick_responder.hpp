#pragma once
/// @file
/// The lockstep rule of a reactive process (controller, actuator): one output
/// per input tick. A repeated tick (the plant re-sending after a timeout) is
/// answered with the cached output, so no core ever steps twice on one
/// sample; an older tick is ignored. `compute` may decline (empty result)
/// when another input of the tick is still missing; the tick is then
/// answered when the plant re-sends it.

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"
#include "transport/process.hpp"

namespace lagrange::transport {

/// Returns the cached output (the answer to the newest tick), for re-sending.
template <class In, class Out>
std::shared_ptr<const std::optional<Out>> respondPerTick(
    LcmNode& node, const std::string& in_channel, const std::string& out_channel, int joints,
    Progress& progress, std::function<std::optional<Out>(const In&)> compute) {
  auto cached = std::make_shared<std::optional<Out>>();
  node.subscribe<In>(
      in_channel, [joints](const In& m) { return validate(m, joints); },
      [&node, &progress, out_channel, compute, cached](const In& m) {
        if (m.header.tick <= progress.last_tick) {
          if (m.header.tick == progress.last_tick && *cached) node.publish(out_channel, **cached);
          return;
        }
        std::optional<Out> out = compute(m);
        if (!out) return;  // not ready: the sender re-sends this tick
        *cached = std::move(out);
        node.publish(out_channel, **cached);
        progress = {m.header.tick, m.header.sim_time};
      });
  return cached;
}

}  // namespace lagrange::transport
