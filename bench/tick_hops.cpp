#include "tick_hops.hpp"

#include <algorithm>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <vector>

#include "median.hpp"
#include "transport/channels.hpp"
#include "transport/safe_decode.hpp"

namespace lagrange::bench {

std::optional<TickHops> tickHops(const std::string& log_path) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) return std::nullopt;
  // Per channel and tick: the first copy's publish time.
  std::map<std::string, std::map<int64_t, int64_t>> published;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    transport::withChannelMessage(e->channel, false, [&](auto msg) {
      if (!transport::safeDecode(e->data, e->datalen, msg)) return false;
      published[e->channel].emplace(msg.header.tick, msg.header.publish_utime);
      return true;
    });
  }
  const auto& position = published[transport::kPlantPosition];
  const auto& command = published[transport::kControlCommand];
  const auto& state = published[transport::kActuatorState];
  std::vector<double> controller, actuator, plant, tick;
  for (const auto& [k, p] : position) {
    const auto c = command.find(k), a = state.find(k), next = position.find(k + 1);
    if (c == command.end() || a == state.end() || next == position.end()) continue;
    controller.push_back(static_cast<double>(c->second - p));
    actuator.push_back(static_cast<double>(a->second - c->second));
    plant.push_back(static_cast<double>(next->second - a->second));
    tick.push_back(static_cast<double>(next->second - p));
  }
  if (tick.size() < 100) return std::nullopt;
  return TickHops{median(controller), median(actuator), median(plant), median(tick)};
}

}  // namespace lagrange::bench
