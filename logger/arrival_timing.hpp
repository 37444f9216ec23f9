#pragma once
/// @file
/// A loop timed from outside: the arrivals of one channel's messages (the
/// first copy of each tick), as the logger hears them. A program from
/// outside in the controller's place reports no loop statistics of its own
/// (issue #46); in realtime its loop is then judged by when its commands
/// come, against the period they should come at -- summary.json
/// `timing.loops.controller` with `measured_by` saying so. Pure: the caller
/// gives the times.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <set>

#include "transport/sample_histogram.hpp"

namespace lagrange::logger {

class ArrivalTiming {
 public:
  explicit ArrivalTiming(double period) : period_(period) {}
  /// A message of `tick` arrived at `t` [s]; copies of a tick already heard
  /// count once.
  void arrived(int64_t tick, double t);
  /// The loop entry of summary.json (docs/summary.md, timing.loops): period,
  /// cycles (messages heard), achieved_rate, jitter (|interval - period|),
  /// deadline_misses (the periods that passed without a message: an interval
  /// of N periods, rounded, missed N - 1), on_time_fraction (cycles / (cycles
  /// + misses)), longest_miss_run (the most periods missed in a row: one
  /// gap's), measured_by;
  /// null when fewer than two arrived.
  nlohmann::json loopJson() const;

 private:
  double period_;
  std::set<int64_t> heard_;  ///< ticks heard (a realtime run's commands: one a period)
  double first_ = 0.0, last_ = 0.0;
  int64_t arrivals_ = 0;
  int64_t misses_ = 0, longest_miss_run_ = 0;
  transport::SampleHistogram jitter_;
};

}  // namespace lagrange::logger
