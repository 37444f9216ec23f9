#include "transport/lcm_node.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include "transport/channels.hpp"
#include "util/error.hpp"

namespace lagrange::transport {

LcmNode::LcmNode(const std::string& process_name, const std::string& url, int64_t run_id)
    : process_name_(process_name),
      lcm_(url),
      run_id_(run_id),
      pid_(static_cast<int32_t>(getpid())),
      newest_only_(run_id),
      reordered_(run_id) {
  if (!lcm_.good())
    throw lagrange::RuntimeFault(process_name + ": cannot open LCM at '" + url +
                                 "'; expected a working LCM URL such as udpm://239.255.76.67:7667?ttl=0 "
                                 "and a network interface with multicast enabled");
}

void LcmNode::authenticate(const MessageKey& key) { auth_ = std::make_unique<MessageAuthenticator>(key); }

bool LcmNode::authentic(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  if (!auth_) return true;
  const auto* data = static_cast<const uint8_t*>(rbuf->data);
  const size_t size = rbuf->data_size;
  // The same datagram dispatched to another handler: the same buffer and
  // receive time, and -- what makes the reuse safe -- the very same bytes.
  if (rbuf == last_checked_rbuf_ && rbuf->recv_utime == last_checked_utime_ && size == last_checked_.size() &&
      std::equal(data, data + size, last_checked_.begin()))
    return last_checked_valid_;  // verified (or rejected and counted) once
  last_checked_rbuf_ = rbuf;
  last_checked_utime_ = rbuf->recv_utime;
  last_checked_.assign(data, data + size);
  last_checked_valid_ = auth_->verify(data, size);
  if (!last_checked_valid_)
    reject(channel, RejectReason::kUnauthenticated,
           "no valid MAC with this run's key (forged, altered on the way, or from a program without the "
           "key; " +
               std::to_string(size) + " bytes)");
  return last_checked_valid_;
}

void LcmNode::subscribeRaw(const std::string& channel_regex,
                           std::function<void(const lcm::ReceiveBuffer*, const std::string&)> handle) {
  handlers_.push_back(std::make_unique<RawHandler>(RawHandler{
      [this, handle = std::move(handle)](const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
        if (lostOnReceive(rbuf, channel) || !authentic(rbuf, channel)) return;
        if (!auth_) return handle(rbuf, channel);
        lcm::ReceiveBuffer payload = *rbuf;  // the handler sees the message without its trailer
        payload.data_size -= static_cast<uint32_t>(kMacBytes);
        handle(&payload, channel);
      }}));
  // subscribeFunction, not subscribe(channel, &Class::method, object): LCM
  // calls the latter through `(handler->*method)(...)`, which GCC 12's
  // -fsanitize=vptr miscompiles (a false "invalid vptr" report, and a
  // segfault with vptr alone). A plain function keeps UBSan's vptr check on.
  lcm::Subscription* sub =
      lcm_.subscribeFunction(channel_regex, &RawHandler::onMessage, handlers_.back().get());
  sub->setQueueCapacity(kQueueCapacity);
}

bool LcmNode::handle(int timeout_ms) {
  if (lcm_.handleTimeout(timeout_ms) >= 0) return true;
  return errno == EINTR;  // a signal interrupted the wait: not an LCM failure
}

int LcmNode::drain(int max_messages) {
  int handled = 0;
  while (handled < max_messages && lcm_.handleTimeout(0) > 0) ++handled;
  return handled;
}

std::string LcmNode::lastInvalid() const {
  std::string all;
  for (const auto& [channel, c] : counters_)
    if (!c.last_invalid.empty()) all += (all.empty() ? "" : "; ") + channel + ": " + c.last_invalid;
  return all;
}

void LcmNode::reject(const std::string& channel, RejectReason why, const std::string& detail) {
  ChannelCounters& c = counters_[channel];
  c.rejected++;
  c.rejected_by[static_cast<size_t>(why)]++;
  // Logged once per kind: per reason, and for invalid messages per detail
  // (the others carry numbers that change with every message).
  const std::string kind =
      std::to_string(static_cast<int>(why)) + (why == RejectReason::kInvalid ? detail : "");
  if (reported_.insert(channel + "\n" + kind).second)
    spdlog::warn(
        fmt::format("{}: rejected a message on {}: {} (further ones of this kind are counted, not logged)",
                    process_name_, channel, detail));
}

void LcmNode::injectFaults(const std::map<std::string, FaultRule>& rules, uint64_t seed) {
  faults_ = std::make_unique<FaultInjector>(lcm_, rules, seed);
}

void LcmNode::loseOnReceive(double probability, uint64_t seed) {
  receive_loss_ = probability;
  receive_seed_ = seed;
}

bool LcmNode::lostOnReceive(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  if (receive_loss_ <= 0.0) return false;
  // splitmix64 of the bytes' FNV-1a and the seed: a uniform draw in [0, 1)
  // that is the same for every handler this datagram is dispatched to.
  uint64_t x = fnv1a(static_cast<const uint8_t*>(rbuf->data), rbuf->data_size) ^ receive_seed_;
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  if (static_cast<double>(x >> 11) * 0x1.0p-53 >= receive_loss_) return false;
  if (rbuf != last_lost_ || rbuf->recv_utime != last_lost_utime_) {
    counters_[channel].lost_on_receive++;
    last_lost_ = rbuf;
    last_lost_utime_ = rbuf->recv_utime;
  }
  return true;
}

void LcmNode::stamp(const std::string& channel, lagrange::header_t& header) const {
  header.run_id = run_id_;
  header.publisher = process_name_;
  header.publisher_pid = pid_;
  const auto it = counters_.find(channel);
  header.seq = (it == counters_.end() ? 0 : it->second.published) + 1;
}

bool LcmNode::admit(const std::string& channel, const lagrange::header_t& h, Order order) {
  HeaderAdmission& admission = order == Order::kNewestOnly ? newest_only_ : reordered_;
  const std::optional<Refusal> refused = admission.admit(channel, h, order);
  if (refused) reject(channel, refused->reason, refused->detail);
  return !refused;
}

bool LcmNode::oversized(const std::string& channel, std::size_t size) const {
  if (!shape_) return false;
  const long long largest = largestPerTickMessage(channel, *shape_);
  return largest >= 0 && static_cast<long long>(size) > largest;
}

void LcmNode::noteError(const std::string& channel, const std::string& what) {
  if (reported_.insert(channel + "\n" + what).second)
    spdlog::error(fmt::format("{}: {} on {}", process_name_, what, channel));
}

std::vector<lagrange::channel_stats_t> LcmNode::channelStats() const {
  std::vector<lagrange::channel_stats_t> out;
  for (const auto& [channel, c] : counters_) {
    lagrange::channel_stats_t s{};
    s.channel = channel;
    s.published = c.published;
    s.received = c.received;
    s.rejected = c.rejected;
    s.rejected_undecodable = c.rejected_by[static_cast<size_t>(RejectReason::kUndecodable)];
    s.rejected_other_run = c.rejected_by[static_cast<size_t>(RejectReason::kOtherRun)];
    s.rejected_wrong_publisher = c.rejected_by[static_cast<size_t>(RejectReason::kWrongPublisher)];
    s.rejected_old_or_repeated = c.rejected_by[static_cast<size_t>(RejectReason::kOldOrRepeated)];
    s.rejected_invalid = c.rejected_by[static_cast<size_t>(RejectReason::kInvalid)];
    s.rejected_corrupt = c.rejected_by[static_cast<size_t>(RejectReason::kCorrupt)];
    s.rejected_unauthenticated = c.rejected_by[static_cast<size_t>(RejectReason::kUnauthenticated)];
    if (faults_) {
      const InjectedCounts injected = faults_->counts(channel);
      s.injected_dropped = injected.dropped;
      s.injected_duplicated = injected.duplicated;
      s.injected_reordered = injected.reordered;
      s.injected_delayed = injected.delayed;
      s.injected_corrupted = injected.corrupted;
    }
    s.injected_lost_on_receive = c.lost_on_receive;
    out.push_back(s);
  }
  return out;
}

}  // namespace lagrange::transport
