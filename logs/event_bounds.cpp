#include "logs/event_bounds.hpp"

#include <utility>

#include "config/input_file.hpp"
#include "config/work_bounds.hpp"
#include "transport/channels.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::logs {

MessageShape shapeOf(int joints, int actuator_order, int torque_steps) {
  // xi_error has a row per stage of the controller's cascade, which is not
  // the actuator's order (the flexible-joint controller reports 2 stages
  // with actuator.order 0): no controller has more than the highest order.
  return {joints, actuator_order, torque_steps, config::kMaxActuatorOrder};
}

MessageShape projectLimits() {
  return shapeOf(config::kMaxJoints, config::kMaxActuatorOrder, static_cast<int>(config::kMaxStepsPerSample));
}

long long maxScenarioEventBytes() {
  return static_cast<long long>(config::kMaxScenarioBytes + 2 * config::kMaxUrdfBytes) + (64 << 10);
}

EventBounds::EventBounds(const MessageShape& shape, std::string origin, long long last_tick)
    : shape_(shape), origin_(std::move(origin)), last_tick_(last_tick) {
  // A stock lcm-logger records the datagrams with their MAC trailer.
  for (const transport::ChannelInfo& info : transport::kChannelTable)
    if (info.per_tick)
      largest_[info.name] =
          transport::largestPerTickMessage(info.name, shape) + static_cast<long long>(transport::kMacBytes);
  largest_[transport::kStatus] = kMaxStatusEventBytes;
  largest_[transport::kScenario] = maxScenarioEventBytes();
  largest_[transport::kRobotDescription] = kMaxDescriptionEventBytes;
}

EventBounds EventBounds::projectLimits(const std::string& why) {
  const MessageShape limits = logs::projectLimits();
  return EventBounds(limits, why + ": the project's limits (" + limits.describe() + ")");
}

long long EventBounds::largestData(const std::string& channel) const {
  const auto it = largest_.find(channel);
  return it == largest_.end() ? -1 : it->second;
}

}  // namespace lagrange::logs
