#pragma once
/// @file
/// What a stalled run says (lockstep.stall_timeout): the plant, which drives
/// the clock, waited too long for a tick's answer or for the logger. It
/// names whom it waited for, on which channel, and what was seen instead,
/// from the latest STATUS of every other process (each carries its channel
/// counters) and its own counters -- e.g. "no valid CONTROL_COMMAND for tick 0
/// reached the actuator in 10 s; it rejected 214 (214 unauthenticated)".
/// Pure: the plant's loop gathers the facts, this puts them in words.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "lagrange/channel_stats_t.hpp"
#include "lagrange/status_t.hpp"
#include "util/error.hpp"

namespace lagrange::plant {

/// A wait of the run ran out (lockstep.stall_timeout): the plant stops the
/// run (exit 1) with the diagnosis as its message.
class PlantStalled : public lagrange::RuntimeFault {
 public:
  using lagrange::RuntimeFault::RuntimeFault;
};

/// What the plant knows when a wait runs out.
struct StallFacts {
  int64_t tick = 0;    ///< the tick awaited (its answer, or the logger before it goes out)
  double seconds = 0;  ///< how long it waited
  /// The newest STATUS of each other process heard ("logger", "controller", "actuator").
  std::map<std::string, lagrange::status_t> peers;
  /// The plant's own counters (channelStats()): what reached it and what it rejected.
  std::vector<lagrange::channel_stats_t> own;
};

/// The rejections of one channel in words, e.g. "214 (200 unauthenticated,
/// 14 invalid)"; "" when there were none.
std::string describeRejections(const lagrange::channel_stats_t& stats);

/// Lockstep: no ACTUATOR_STATE answered `facts.tick` in time. Follows the
/// ring back from the plant: the actuator's answer, the controller's
/// command, the controller's input.
std::string describeAnswerStall(const StallFacts& facts);

/// Lockstep: the logger did not confirm the ticks before `facts.tick` in time
/// (`confirmed`: the last tick it confirmed, -1 for none; it may not have been heard at all).
std::string describeLoggerStall(const StallFacts& facts, int64_t confirmed);

/// The start of a run: not every process in `expected` reported (STATUS) in time.
std::string describeMissingPeers(const StallFacts& facts, const std::vector<std::string>& expected);

}  // namespace lagrange::plant
