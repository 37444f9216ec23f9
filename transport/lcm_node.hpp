#pragma once
/// @file
/// The one place where a process touches LCM: publishing with counters, and
/// typed subscriptions that decode and validate by hand so that a malformed
/// message is rejected, counted and logged once per kind, never crashes the
/// process and never reaches the mathematics.

#include <array>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "lagrange/channel_stats_t.hpp"
#include "lagrange/header_t.hpp"
#include "transport/checksum.hpp"
#include "transport/fault_injector.hpp"
#include "transport/header_admission.hpp"
#include "transport/message_auth.hpp"
#include "transport/message_size.hpp"
#include "transport/safe_decode.hpp"

namespace lagrange::transport {

/// Why a message was rejected (empty string: accepted).
using Rejection = std::string;

struct ChannelCounters {
  long long published = 0;
  long long received = 0;
  long long rejected = 0;
  std::array<long long, kRejectReasons> rejected_by = {};  ///< indexed by RejectReason
  long long lost_on_receive = 0;                           ///< injected: faults.receivers
  /// Why the last message refused as invalid was, and whose (empty: none).
  std::string last_invalid;
};

/// True for the project's message types: they carry a header_t.
template <class T, class = void>
struct HasHeader : std::false_type {};
template <class T>
struct HasHeader<T, std::void_t<decltype(std::declval<T>().header)>> : std::true_type {};

class LcmNode {
 public:
  /// @param run_id the run's identity, stamped on every message published and
  ///        required of every message received; 0: a process on its own,
  ///        which stamps 0 and accepts any run.
  /// @throws lagrange::RuntimeFault naming the URL if LCM cannot be initialised.
  LcmNode(const std::string& process_name, const std::string& url, int64_t run_id = 0);
  int64_t runId() const { return run_id_; }

  /// From now on every message published carries the MAC trailer of `key`
  /// (message_auth.hpp), and every datagram received must carry a valid one:
  /// one that does not is dropped before any decoding and counted as
  /// rejected (unauthenticated) on its channel. Handlers, raw ones
  /// included, see the payload without the trailer. Without a key a node
  /// neither signs nor checks (a process on its own, tests).
  void authenticate(const MessageKey& key);

  /// From now on a datagram on a per-tick channel larger than the largest
  /// honest message of `shape` (message_size.hpp) is rejected as
  /// undecodable before it is decoded: the decoders may allocate 64 bytes
  /// per byte received, and a holder of the key could send 256 MB.
  void boundMessages(const MessageShape& shape) { shape_ = shape; }
  /// True when `size` bytes on `channel` (without the MAC trailer) exceed
  /// the bound of boundMessages (never without one).
  bool oversized(const std::string& channel, std::size_t size) const;

  /// What a subscription does with a datagram older than the newest one of
  /// its publisher (HeaderAdmission::Order: refuse it, or accept it once).
  using Order = HeaderAdmission::Order;

  /// Subscribe to a channel with type Msg. `validate` returns an empty string
  /// to accept, or the reason to reject; `handle` sees accepted messages only.
  template <class Msg>
  void subscribe(const std::string& channel, std::function<Rejection(const Msg&)> validate,
                 std::function<void(const Msg&)> handle, Order order = Order::kNewestOnly);

  /// Publishes `msg`, its header stamped with the run, this publisher and the next sequence number.
  template <class Msg>
  void publish(const std::string& channel, const Msg& msg) {
    int rc = 0;
    if constexpr (HasHeader<Msg>::value) {
      Msg stamped = msg;
      stamp(channel, stamped.header);
      seal(stamped);
      rc = send(channel, stamped);
    } else {
      rc = send(channel, msg);
    }
    if (rc != 0) noteError(channel, "publish failed");
    counters_[channel].published++;
  }

  /// From now on, what this node publishes passes through seeded fault injection (config faults.*).
  void injectFaults(const std::map<std::string, FaultRule>& rules, uint64_t seed);

  /// From now on, each datagram reaching this node is lost for it with this
  /// probability (config faults.receivers), before any handler sees it:
  /// decided by a seeded hash of its bytes, so every subscription of the
  /// node agrees, and counted once per datagram.
  void loseOnReceive(double probability, uint64_t seed);

  /// Every message on channels matching the regex, undecoded (but
  /// authenticated, and without its MAC trailer, when the node has a key).
  /// The queue is deep (kQueueCapacity) so a slow handler does not silently
  /// drop messages.
  void subscribeRaw(const std::string& channel_regex,
                    std::function<void(const lcm::ReceiveBuffer*, const std::string&)> handle);

  static constexpr int kQueueCapacity = 100000;

  /// Process incoming messages for up to timeout_ms; returns false on an LCM error.
  bool handle(int timeout_ms);

  /// Handle every message already waiting, without blocking (at most
  /// max_messages, so a flood cannot hold the caller). Returns how many.
  int drain(int max_messages = 1000);

  /// Wall-clock receive time [us] of the message being handled.
  int64_t lastReceiveUtime() const { return last_receive_utime_; }

  const std::map<std::string, ChannelCounters>& counters() const { return counters_; }
  std::vector<lagrange::channel_stats_t> channelStats() const;
  /// The last message of the run's own publishers refused as invalid, per
  /// channel ("CONTROL_COMMAND: u[0] is not finite (from 'controller', tick
  /// 531)"), joined by "; " -- empty when none was. STATUS carries it, so that
  /// a stall names what was wrong and who sent it.
  std::string lastInvalid() const;
  const std::string& processName() const { return process_name_; }
  lcm::LCM& raw() { return lcm_; }

 private:
  template <class Msg>
  int send(const std::string& channel, const Msg& msg) {
    if (!faults_ && !auth_) return lcm_.publish(channel, &msg);
    // One buffer per thread, reused: no allocation per message once warm.
    thread_local std::vector<uint8_t> bytes;
    bytes.resize(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    // Signed before fault injection: a corrupted copy fails the check, as it would on a wire.
    if (auth_) auth_->sign(bytes);
    if (faults_) return faults_->publish(channel, bytes);
    return lcm_.publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size()));
  }
  /// Whether a datagram carries a valid MAC (true without a key); rejects
  /// and counts it if not. A datagram dispatched to several handlers of
  /// this node is hashed and counted once: only the very same bytes reuse
  /// the last verdict (never just the same buffer address).
  bool authentic(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void reject(const std::string& channel, RejectReason why, const std::string& detail);
  void stamp(const std::string& channel, lagrange::header_t& header) const;
  /// Whether a received header belongs here (HeaderAdmission: this run, the
  /// channel's publisher, a newer sequence number of its current process).
  /// Rejects (and returns false) if not.
  bool admit(const std::string& channel, const lagrange::header_t& header, Order order);
  void noteError(const std::string& channel, const std::string& what);

  std::string process_name_;
  lcm::LCM lcm_;
  std::map<std::string, ChannelCounters> counters_;
  std::set<std::string> reported_;  ///< channel/reason pairs already logged
  int64_t last_receive_utime_ = 0;
  std::unique_ptr<MessageAuthenticator> auth_;
  std::optional<MessageShape> shape_;
  const lcm::ReceiveBuffer* last_checked_rbuf_ = nullptr;  ///< the datagram authentic() checked last:
  int64_t last_checked_utime_ = -1;                        ///< its buffer, receive time,
  std::vector<uint8_t> last_checked_;                      ///< bytes
  bool last_checked_valid_ = false;                        ///< and verdict
  std::unique_ptr<FaultInjector> faults_;  // after lcm_: stopped (its last sends made) before LCM closes
  int64_t run_id_ = 0;
  int32_t pid_ = 0;
  double receive_loss_ = 0.0;
  uint64_t receive_seed_ = 0;
  const lcm::ReceiveBuffer* last_lost_ = nullptr;  ///< the datagram counted last (one per handler pass)
  int64_t last_lost_utime_ = -1;
  bool lostOnReceive(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  /// One per order: a channel is read one way, but a test may read a channel both ways.
  HeaderAdmission newest_only_;
  HeaderAdmission reordered_;

  struct RawHandler {
    std::function<void(const lcm::ReceiveBuffer*, const std::string&)> fn;
    static void onMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel, RawHandler* self) {
      self->fn(rbuf, channel);
    }
  };
  std::vector<std::unique_ptr<RawHandler>> handlers_;
};

template <class Msg>
void LcmNode::subscribe(const std::string& channel, std::function<Rejection(const Msg&)> validate,
                        std::function<void(const Msg&)> handle, Order order) {
  counters_[channel];
  auto callback = [this, channel, validate, handle, order](const lcm::ReceiveBuffer* rbuf,
                                                           const std::string&) {
    if (oversized(channel, rbuf->data_size))
      return reject(channel, RejectReason::kUndecodable,
                    std::to_string(rbuf->data_size) + " bytes, more than any " + channel + " of this run (" +
                        shape_->describe() + ") can be: " +
                        std::to_string(largestPerTickMessage(channel, *shape_)) + " bytes; not decoded");
    Msg msg;
    if (!safeDecode(rbuf->data, rbuf->data_size, msg))
      return reject(channel, RejectReason::kUndecodable, "undecodable (wrong type, size or corrupt bytes)");
    if constexpr (HasHeader<Msg>::value) {
      if (!intact(msg))
        return reject(channel, RejectReason::kCorrupt, "checksum mismatch (bytes changed on the way)");
      if (!admit(channel, msg.header, order)) return;
    }
    const Rejection why = validate(msg);
    if (!why.empty()) {
      if constexpr (HasHeader<Msg>::value)
        // At most 240 bytes of the reason (publisher names are bounded too):
        // STATUS stays far below its bound (logs/event_bounds.hpp).
        counters_[channel].last_invalid = why.substr(0, 240) + " (from '" + msg.header.publisher +
                                          "', tick " + std::to_string(msg.header.tick) + ")";
      return reject(channel, RejectReason::kInvalid, why);
    }
    counters_[channel].received++;
    last_receive_utime_ = rbuf->recv_utime;
    handle(msg);
  };
  subscribeRaw(channel, callback);
}

}  // namespace lagrange::transport
