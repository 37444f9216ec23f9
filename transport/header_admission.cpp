#include "transport/header_admission.hpp"

#include <algorithm>

#include "lagrange/run_join_t.hpp"
#include "lagrange/status_t.hpp"
#include "transport/channels.hpp"
#include "transport/safe_decode.hpp"

namespace lagrange::transport {

std::optional<Refusal> HeaderAdmission::admit(const std::string& channel, const lagrange::header_t& h,
                                              Order order) {
  if (run_id_ != 0 && h.run_id != run_id_)
    return Refusal{RejectReason::kOtherRun, "from another run (run_id " + std::to_string(h.run_id) +
                                                ", this run is " + std::to_string(run_id_) + "; publisher '" +
                                                h.publisher + "')"};
  const std::string expected = publisherOf(channel);
  if (!expected.empty() && h.publisher != expected)
    return Refusal{RejectReason::kWrongPublisher,
                   "published by '" + h.publisher + "', expected '" + expected + "'"};
  Succession& s = publishers_[channel + "\n" + h.publisher];
  const bool new_process = s.started && h.publisher_pid != s.current_pid;
  if (new_process) {
    if (auto refused = refuseSuccession(s, channel, h)) return refused;
  }
  // A process that takes over starts a window of its own (its numbers start at 1).
  Window taken_over;
  Window& w = new_process || !s.started ? taken_over : s.window;
  if (order == Order::kAcceptReordered) {
    // A window of the newest kSequenceWindow numbers: inside it a number
    // counts once, in any order; below it nothing counts (it is older than
    // any reordering -- a replay).
    if (h.seq <= 0 || h.seq <= w.newest - kSequenceWindow || !w.seen.insert(h.seq).second)
      return Refusal{RejectReason::kOldOrRepeated,
                     "sequence number " + std::to_string(h.seq) + " of '" + h.publisher +
                         "' seen before or older than the window (a duplicate or a replay)"};
    w.newest = std::max(w.newest, h.seq);
    while (*w.seen.begin() <= w.newest - kSequenceWindow) w.seen.erase(w.seen.begin());
  } else {
    if (h.seq <= w.newest)
      return Refusal{RejectReason::kOldOrRepeated, "sequence number " + std::to_string(h.seq) + " of '" +
                                                       h.publisher + "' not newer than " +
                                                       std::to_string(w.newest) +
                                                       " (a duplicate or reordered datagram)"};
    w.newest = h.seq;
  }
  if (new_process) s.replaced.insert(s.current_pid);
  if (new_process || !s.started) {
    s.window = std::move(taken_over);
    s.current_pid = h.publisher_pid;
    s.newest_utime = h.publish_utime;
    s.started = true;
  }
  s.newest_utime = std::max(s.newest_utime, h.publish_utime);
  return std::nullopt;
}

// A pid other than the publisher's current one: a later process of the same
// name takes over (a restart); never one it replaced, nor one whose message
// is no later than what the current one sent.
std::optional<Refusal> HeaderAdmission::refuseSuccession(const Succession& s, const std::string& channel,
                                                         const lagrange::header_t& h) {
  if (s.replaced.count(h.publisher_pid) != 0)
    return Refusal{RejectReason::kOldOrRepeated, "from pid " + std::to_string(h.publisher_pid) + " of '" +
                                                     h.publisher + "', which pid " +
                                                     std::to_string(s.current_pid) + " replaced on " +
                                                     channel + " (a replay of an earlier process)"};
  if (h.publish_utime <= s.newest_utime)
    return Refusal{RejectReason::kOldOrRepeated,
                   "from pid " + std::to_string(h.publisher_pid) + " of '" + h.publisher +
                       "', published at " + std::to_string(h.publish_utime) +
                       " us, no later than the newest message of pid " + std::to_string(s.current_pid) +
                       " (" + std::to_string(s.newest_utime) + " us) on " + channel +
                       ": a replay of an earlier process, not a restart"};
  return std::nullopt;
}

namespace {
template <class Msg>
bool peekAs(const void* data, std::size_t size, lagrange::header_t& out) {
  if (size < 8) return false;
  int64_t hash = 0;
  if (__int64_t_decode_array(data, 0, static_cast<int>(size), &hash, 1) != 8 || hash != Msg::getHash())
    return false;
  try {
    const AllocationBudget budget(decodeBudget(size));
    return out._decodeNoHash(data, 8, static_cast<int>(size) - 8) > 0;
  } catch (const std::exception&) {  // a string longer than the datagram: over budget
    return false;
  }
}
}  // namespace

bool carriesHeader(const std::string& channel) {
  return channel == kStatus || channel == kRunJoin ||
         withChannelMessage(channel, false, [](auto) { return true; });
}

bool peekHeader(const std::string& channel, const void* data, std::size_t size, lagrange::header_t& out) {
  if (size > static_cast<std::size_t>(INT32_MAX)) return false;
  if (channel == kStatus) return peekAs<lagrange::status_t>(data, size, out);
  if (channel == kRunJoin) return peekAs<lagrange::run_join_t>(data, size, out);
  return withChannelMessage(channel, false,
                            [&](auto type) { return peekAs<decltype(type)>(data, size, out); });
}

}  // namespace lagrange::transport
