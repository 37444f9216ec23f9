#pragma once
/// @file
/// The realtime loop of a reactive process (controller, actuator): wake at a
/// fixed rate, take the newest input (latest-value semantics), act on it once
/// if it is fresh, skip it (counted as stale) if it is older than
/// max_input_age, and report loop statistics in STATUS until the plant
/// finishes or a stop signal arrives. `compute` may decline an input it
/// cannot answer yet (a controller whose PLANT_RATE of that tick is missing):
/// counted as missing.

#include <functional>
#include <optional>
#include <string>

#include "runtime/process.hpp"
#include "runtime/status_reporter.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"
#include "transport/rate_loop.hpp"

namespace lagrange::runtime {

struct RealtimeSettings {
  double period = 1e-3;         ///< [s]
  double phase = 0.0;           ///< fraction of a period after the plant's deadlines
  double max_input_age = 5e-3;  ///< [s]
};

/// `Node` is transport::LcmNode in the processes (a fake node in tests).
template <class In, class Out, class Node>
int serveRealtime(Node& node, const std::string& in_channel, const std::string& out_channel, int joints,
                  const RealtimeSettings& settings,
                  const std::function<std::optional<Out>(const In&)>& compute) {
  std::optional<In> latest;
  node.template subscribe<In>(
      in_channel, [joints](const In& m) { return transport::validate(m, joints); },
      [&latest](const In& m) {
        if (!latest || m.header.tick > latest->header.tick) latest = m;
      });
  bool plant_finished = false;
  watchPlantFinished(node, plant_finished);

  BasicStatusReporter<Node> status(node);
  Progress progress;
  transport::SampleHistogram ages;  // fixed memory: nothing allocated per cycle
  int64_t missing = 0, stale = 0;
  auto stats = [&](const transport::FixedRateLoop& loop) {
    lagrange::loop_stats_t s = loop.stats();
    transport::setInputStats(s, ages, missing, stale);
    return s;
  };

  transport::FixedRateLoop loop(settings.period, settings.phase);
  status.publish(State::kReady, -1, 0.0);
  loop.start();
  auto next_status = transport::monotonicNs() + 500'000'000LL;
  while (!plant_finished && !stopRequested()) {
    loop.waitNext();
    node.drain();
    if (!latest || latest->header.tick <= progress.last_tick) {
      ++missing;
    } else {
      const double age = static_cast<double>(transport::nowUtime() - latest->header.publish_utime) * 1e-6;
      if (age > settings.max_input_age) {
        ++stale;  // never act on an old sample
      } else {
        if (const std::optional<Out> out = compute(*latest)) {
          ages.add(age);
          node.publish(out_channel, *out);
        } else {
          ++missing;
        }
      }
      progress = {latest->header.tick, latest->header.sim_time};
    }
    if (transport::monotonicNs() >= next_status) {
      status.setLoopStats(stats(loop));
      status.publish(State::kRunning, progress.last_tick, progress.sim_time);
      next_status += 500'000'000LL;
    }
  }
  status.setLoopStats(stats(loop));
  status.publish(plant_finished ? State::kFinished : State::kInterrupted, progress.last_tick,
                 progress.sim_time);
  return 0;
}

}  // namespace lagrange::runtime
