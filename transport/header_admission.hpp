#pragma once
/// @file
/// Whether a received message's header belongs to the run (DESIGN section
/// 6): this run's id, the channel's one publisher, and a sequence number
/// newer than anything that publisher sent before -- a duplicate, a
/// reordered datagram or a replay is refused. Pure (no LCM): every
/// validated subscription of a process asks it (LcmNode), and the logger
/// asks its own before it records a datagram, so the log holds what the
/// run's processes would accept.
///
/// A publisher is a process name on a channel. Its sequence numbers start
/// at 1 in each process, so a restarted process (a new pid) starts a window
/// of its own; but only a *later* one: a pid takes over from the one it
/// replaces when its message was published after everything accepted from
/// that one (header.publish_utime, the run's monotonic clock on the host
/// where both ran), and a replaced pid is never heard again. So a recording
/// of an earlier process of the run, re-sent mid-run, cannot open a fresh
/// window: its stamps are older.

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "lagrange/header_t.hpp"

namespace lagrange::transport {

/// Why a message was rejected (channel_stats_t's rejected_* counters).
enum class RejectReason {
  kUndecodable,
  kOtherRun,
  kWrongPublisher,
  kOldOrRepeated,
  kInvalid,
  kCorrupt,
  kUnauthenticated  ///< no valid MAC with the run's key: forged, altered, or from a program without the key
};
inline constexpr int kRejectReasons = 7;

/// The reason's name in summary.json (rejected_by_reason).
inline const char* reasonName(RejectReason reason) {
  switch (reason) {
    case RejectReason::kUndecodable:
      return "undecodable";
    case RejectReason::kOtherRun:
      return "other_run";
    case RejectReason::kWrongPublisher:
      return "wrong_publisher";
    case RejectReason::kOldOrRepeated:
      return "old_or_repeated";
    case RejectReason::kInvalid:
      return "invalid";
    case RejectReason::kCorrupt:
      return "corrupt";
    case RejectReason::kUnauthenticated:
      return "unauthenticated";
  }
  return "?";
}

/// A refusal: its reason and a sentence for the log.
struct Refusal {
  RejectReason reason;
  std::string detail;
};

class HeaderAdmission {
 public:
  /// What to do with a datagram older than the newest one of its publisher.
  enum class Order {
    kNewestOnly,      ///< refuse it (old_or_repeated): inputs of the mathematics, where late means stale
    kAcceptReordered  ///< accept it unless it is a repeat: records, where a late sample is still a sample
  };
  /// Order::kAcceptReordered: how far behind its publisher's newest a
  /// sequence number may be and still count (once).
  static constexpr int64_t kSequenceWindow = 100000;

  /// @param run_id the run's identity; 0: accept any run.
  explicit HeaderAdmission(int64_t run_id) : run_id_(run_id) {}

  /// Nothing when `h` is admitted on `channel` (and remembered: the same
  /// header is refused the next time), else why not.
  std::optional<Refusal> admit(const std::string& channel, const lagrange::header_t& h, Order order);

 private:
  /// One publisher's process on one channel and the numbers it used.
  struct Window {
    int64_t newest = 0;
    std::set<int64_t> seen;  ///< kAcceptReordered: the numbers accepted within kSequenceWindow of the newest
  };
  /// The processes that published as one name on one channel.
  struct Succession {
    bool started = false;  ///< a message was admitted
    int32_t current_pid = 0;
    int64_t newest_utime = 0;  ///< the latest publish_utime accepted from current_pid
    std::set<int32_t> replaced;
    Window window;  ///< current_pid's
  };
  static std::optional<Refusal> refuseSuccession(const Succession& s, const std::string& channel,
                                                 const lagrange::header_t& h);

  int64_t run_id_;
  std::map<std::string, Succession> publishers_;  ///< by channel and publisher name
};

/// True for the project's channels whose messages carry a header_t (all but
/// SCENARIO and ROBOT_DESCRIPTION); false for channels of others.
bool carriesHeader(const std::string& channel);

/// The header of a datagram on one of the project's channels that carry one
/// (the per-tick channels, STATUS, RUN_JOIN) without decoding the rest:
/// false when the channel has none or the bytes are not its message type's
/// (its fingerprint) followed by a whole header.
bool peekHeader(const std::string& channel, const void* data, std::size_t size, lagrange::header_t& out);

}  // namespace lagrange::transport
