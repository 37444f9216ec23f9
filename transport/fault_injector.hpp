#pragma once
/// @file
/// Seeded fault injection on the sending side of LcmNode (config `faults.*`):
/// per channel, a datagram is dropped, corrupted (one byte flipped),
/// duplicated, held back until the next one on the channel has gone out
/// (reordered), or delayed (fixed plus uniform jitter). Every fault is
/// counted; the counts travel in STATUS (channel_stats_t injected_*) into
/// summary.json. Delayed and held datagrams are sent by a thread of their
/// own at their due time (LCM's publish is thread-safe), so the delay does
/// not depend on how often the process polls.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "transport/fault_rule.hpp"

namespace lagrange::transport {

/// Faults injected on one channel so far.
struct InjectedCounts {
  long long dropped = 0, duplicated = 0, reordered = 0, delayed = 0, corrupted = 0;
};

class FaultInjector {
 public:
  /// @param rules per channel; the key "all" applies to channels without their own entry.
  FaultInjector(lcm::LCM& lcm, std::map<std::string, FaultRule> rules, uint64_t seed);
  ~FaultInjector();  ///< sends what is still delayed or held, then stops the thread
  FaultInjector(const FaultInjector&) = delete;
  FaultInjector& operator=(const FaultInjector&) = delete;

  /// Sends `bytes` on `channel` -- or not, or twice, or later, as the rules draw. Returns LCM's status of
  /// the immediate send (0 when nothing was sent now).
  int publish(const std::string& channel, std::vector<uint8_t> bytes);

  InjectedCounts counts(const std::string& channel) const;

 private:
  using Clock = std::chrono::steady_clock;
  struct Pending {
    Clock::time_point due;
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  const FaultRule* rulesFor(const std::string& channel) const;
  void schedule(Pending p);
  void run();
  int send(const std::string& channel, const std::vector<uint8_t>& bytes);

  lcm::LCM& lcm_;
  std::map<std::string, FaultRule> rules_;
  std::mt19937_64 rng_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Pending> pending_;                      // delayed datagrams, any order
  std::map<std::string, std::vector<uint8_t>> held_;  // per channel: the datagram held for reordering
  std::map<std::string, InjectedCounts> counts_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace lagrange::transport
