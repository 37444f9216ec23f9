#pragma once
/// @file
/// A fixed-rate loop on the monotonic clock with absolute deadlines (no
/// drift), and the statistics a realtime process reports about it.
///
/// Deadlines sit at whole multiples of the period plus a phase, on
/// CLOCK_MONOTONIC, which every process on one host shares: plant,
/// controller and actuator, started at different moments, still wake in a
/// fixed order within each period.

#include <sched.h>

#include <cstdint>
#include <string>
#include <vector>

#include "lagrange/loop_stats_t.hpp"
#include "transport/sample_histogram.hpp"

namespace lagrange::transport {

/// Median, 99th percentile and maximum of a sample, exactly (by sorting it).
Percentiles percentiles(std::vector<double> samples);

class FixedRateLoop {
 public:
  /// period [s] > 0; phase in [0, 1) of a period.
  FixedRateLoop(double period, double phase);

  /// Sets the first deadline: the next one after now.
  void start();

  /// Sleeps until the next deadline (at once if it has passed, counting a
  /// miss) and records the wake-up lateness.
  void waitNext();

  /// Deadline-related fields of the statistics (the rest stay zero).
  lagrange::loop_stats_t stats() const;

 private:
  int64_t period_ns_, phase_ns_;
  int64_t start_ns_ = 0, next_ns_ = 0;
  int64_t cycles_ = 0, misses_ = 0, miss_run_ = 0, longest_miss_run_ = 0;
  SampleHistogram lateness_;  ///< wake-up lateness [s]: fixed memory, however long the run
  std::string scheduler_;
};

int64_t monotonicNs();

/// Fills the input-side fields of loop statistics: the age at use of the
/// inputs acted on [s], and the counts of cycles without a new input and with
/// a stale one.
void setInputStats(lagrange::loop_stats_t& stats, const SampleHistogram& ages, int64_t missing,
                   int64_t stale);

/// Asks for SCHED_FIFO at `priority` for this process and locks its memory
/// (mlockall), as realtime robot software does. Call it before any thread is
/// created (LCM's receive thread inherits the policy, so the thread that
/// delivers inputs is not starved by the loop threads). Returns the policy in
/// effect: "fifo:PRIORITY", or "other" where FIFO is not allowed (no root, no
/// CAP_SYS_NICE) or priority is 0.
std::string enterRealtimeScheduling(int priority);

/// @throws BadInput naming `key` and the machine's CPUs when one of `cpus` is
///         not among its online CPUs.
void checkCpus(const std::vector<int>& cpus, const std::string& key);

/// Keeps this process (and the threads it starts after) on `cpus` (checkCpus first).
/// @throws BadInput naming `key` and the machine's CPUs when one is not
///         among them, or the kernel refuses the set.
void pinToCpus(const std::vector<int>& cpus, const std::string& key);

/// The CPUs this process pinned itself to (pinToCpus), "0,2-3"; empty when
/// it did not pin itself.
std::string cpuRestriction();

/// "0,2-3": the CPUs of `set`, as the loops' `scheduler` strings write them.
std::string cpuList(const cpu_set_t& set);

}  // namespace lagrange::transport
