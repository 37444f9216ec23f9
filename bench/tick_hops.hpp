#pragma once
/// @file
/// Where a lockstep tick's wall time goes, read back from its run.lcm: each
/// message's header.publish_utime (first copy per tick) gives the three
/// hops of the tick's ring -- PLANT_POSITION published to its
/// CONTROL_COMMAND published (the controller's hop), to its ACTUATOR_STATE
/// (the actuator's), to the next tick's PLANT_POSITION (the plant's, which
/// steps the physics) -- beside the bare ring's hop (docs/performance.md).

#include <optional>
#include <string>

namespace lagrange::bench {

/// Medians over the log's ticks [us].
struct TickHops {
  double controller = 0, actuator = 0, plant = 0, tick = 0;
};

/// nullopt if the log has fewer than 100 complete ticks.
std::optional<TickHops> tickHops(const std::string& log_path);

}  // namespace lagrange::bench
