#pragma once
/// @file
/// What the logger's STATUS last_tick confirms to the plant, and when it is
/// time to say so (DESIGN section 4), without LCM or clock.
///
/// Lockstep: every message of every tick up to it is in the log -- the
/// plant re-sends the ticks after it (and the controller and actuator
/// answer them again), so a datagram lost on the way to the logger alone is
/// sent again. Realtime (nothing is re-sent): the contiguous samples.
///
/// Progress is acknowledged whenever the confirmed tick has moved ack_every
/// ticks since the last STATUS, so a plant allowed lockstep.logger_window
/// ticks ahead never waits for the logger.

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "logger/tick_coverage.hpp"

namespace lagrange::logger {

class TickConfirmation {
 public:
  /// @param channels the per-tick channels whose every tick must be in the log
  /// @param lockstep whether the run re-sends (lockstep) or not (realtime)
  /// @param logger_window lockstep.logger_window; STATUS every quarter of it
  TickConfirmation(const std::vector<std::string>& channels, int64_t last_tick, bool lockstep,
                   int logger_window)
      : lockstep_(lockstep), ack_every_(std::max(1, logger_window / 4)) {
    for (const std::string& channel : channels) coverage_.emplace(channel, TickCoverage(last_tick));
  }

  /// A message of `channel` for `tick` is in the log; `newest_sample` is the
  /// newest tick of the tracking samples (TrackingMetrics::lastTick()).
  /// Channels not given at construction are ignored.
  void record(const std::string& channel, int64_t tick, int64_t newest_sample) {
    const auto it = coverage_.find(channel);
    if (it == coverage_.end()) return;
    it->second.add(tick);
    if (confirmed(newest_sample) - acked_ >= ack_every_) due_ = true;
  }

  /// The tick STATUS last_tick may confirm now.
  int64_t confirmed(int64_t newest_sample) const {
    int64_t tick = newest_sample;
    if (lockstep_)
      for (const auto& entry : coverage_) tick = std::min(tick, entry.second.contiguousThrough());
    return tick;
  }

  /// Whether enough has been recorded since the last STATUS to send one now.
  bool acknowledgementDue() const { return due_; }
  /// A STATUS goes out: returns the tick it confirms.
  int64_t acknowledge(int64_t newest_sample) {
    acked_ = confirmed(newest_sample);
    due_ = false;
    return acked_;
  }

  /// Per channel, the ticks 0..up_to without a message (summary.json log.missing_ticks).
  std::map<std::string, long long> missingUpTo(int64_t up_to) const {
    std::map<std::string, long long> missing;
    for (const auto& [channel, ticks] : coverage_) missing[channel] = ticks.missingUpTo(up_to);
    return missing;
  }

 private:
  bool lockstep_;
  long long ack_every_;
  std::map<std::string, TickCoverage> coverage_;
  int64_t acked_ = -1;  ///< the last_tick of the last STATUS
  bool due_ = false;
};

}  // namespace lagrange::logger
