#pragma once
/// @file
/// The largest event an honest log can hold on each of the project's
/// channels, so that a larger one is skipped unread instead of decoded.
///
/// Why: the message decoders (transport/safe_decode.hpp) may allocate 64
/// bytes per byte received, and lcm-gen's types cost far more memory than
/// their bytes for many short rows: one ACTUATOR_STATE of 241 MB holding 30
/// million one-joint rows of tau_applied, lengths all consistent, took replay
/// to 3.5 GB. But a log's SCENARIO says how big each per-tick message of the
/// run is: the arm's joints, the actuator's order (rows of xi), the torque
/// steps a tick (rows of tau_applied). An event larger than its
/// channel's message can be with those is not one of the run's messages.
///
/// The bounds are the messages' encoded sizes (transport/message_size.hpp)
/// with every count at the shape's value, a publisher name of up to
/// transport::kMaxPublisherBytes and the MAC trailer a stock lcm-logger
/// recording keeps. Without a scenario (a stock
/// recording started late, a SCENARIO that does not parse) the shape is the
/// project's own limits: the most joints, order and torque steps any
/// scenario may ask for. SCENARIO, ROBOT_DESCRIPTION and STATUS have fixed
/// bounds; channels of other programs have none (they are never decoded).

#include <cstdint>
#include <map>
#include <string>

#include "transport/message_size.hpp"

namespace lagrange::logs {

using transport::MessageShape;

/// The most any scenario may ask for (config/work_bounds.hpp: 16 joints,
/// actuator order 4, 100 000 torque steps a tick; any controller reports at
/// most 4 stages of xi_error): the shape of a log without a usable scenario.
MessageShape projectLimits();
/// The shape of a scenario's per-tick messages: its joints, actuator order
/// and torque steps a tick, and the most stages of xi_error any controller reports.
MessageShape shapeOf(int joints, int actuator_order, int torque_steps);

/// SCENARIO: a scenario file (at most 1 MiB, config/input_file.hpp) resolved
/// with its URDF inline (at most 16 MiB, written escaped: at most twice that),
/// and room for the name and the trailer.
long long maxScenarioEventBytes();
/// ROBOT_DESCRIPTION: 1 MiB, about ten thousand frames and shapes (the Panda's is 2.2 kB).
inline constexpr long long kMaxDescriptionEventBytes = 1 << 20;
/// STATUS: 64 KiB, a few hundred channels' counters and a long message (the golden logs' are under 1.5 kB).
inline constexpr long long kMaxStatusEventBytes = 64 << 10;

/// Per channel, the largest data an event may have in one log.
class EventBounds {
 public:
  /// The log's own scenario made `shape`; `origin` says so in warnings
  /// ("the log's scenario").
  /// `last_tick`: the scenario's last tick; a per-tick event for a tick
  /// outside [0, last_tick] is no message of the run (LogEventReader drops it).
  EventBounds(const MessageShape& shape, std::string origin, long long last_tick = kMostTicks);
  /// The most ticks any scenario may have (config/work_bounds.hpp kMaxSamples):
  /// the tick bound of a log without a usable scenario.
  static constexpr long long kMostTicks = 100000000;
  /// A log without a usable scenario: the project's limits.
  static EventBounds projectLimits(const std::string& why = "no scenario");

  /// The most data bytes an event on `channel` may hold; -1: no bound (a
  /// channel of another program, which the project never decodes).
  long long largestData(const std::string& channel) const;
  /// Whose shape bounds the events, for a warning: "the log's scenario (2
  /// joints, actuator order 0, 1 torque step a tick)".
  const std::string& origin() const { return origin_; }
  const MessageShape& shape() const { return shape_; }
  long long lastTick() const { return last_tick_; }

 private:
  MessageShape shape_;
  std::string origin_;
  long long last_tick_;
  std::map<std::string, long long, std::less<>> largest_;
};

}  // namespace lagrange::logs
