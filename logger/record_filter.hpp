#pragma once
/// @file
/// What the logger records: every authenticated datagram of the run's own
/// processes, once -- the same header checks its processes make
/// (transport::HeaderAdmission: this run's id, the channel's publisher, a
/// sequence number its current process has not used), so that a message of
/// another run or a re-sent copy never lands in run.lcm where `report`,
/// `export` and the Python reader would take it for the run's. What the
/// processes refuse for its content (a NaN, a wrong joint count) is still
/// recorded: it is what the run's processes sent, and the log is their
/// record. Datagrams on channels the project does not know are recorded as
/// before (they passed the MAC when the run has a key). A per-tick message
/// for a tick outside the run's [0, last tick] is not recorded (counted as
/// `outside_run`): no process of the run asks for it, and a log's readers
/// keep memory in proportion to the scenario, not to what was sent.

#include <cstdint>
#include <limits>
#include <map>
#include <string>

#include "transport/channels.hpp"
#include "transport/header_admission.hpp"

namespace lagrange::logger {

class RecordFilter {
 public:
  explicit RecordFilter(int64_t run_id, int64_t last_tick = std::numeric_limits<int64_t>::max())
      : admission_(run_id), last_tick_(last_tick) {}

  /// True when the datagram is to be recorded; else counted by reason.
  /// `oversized`: larger than any message of the channel in this run can be
  /// (transport::LcmNode::oversized): not a message of the run, not read.
  bool admit(const std::string& channel, const void* data, std::size_t size, bool oversized = false) {
    if (oversized) return refuse(channel, transport::RejectReason::kUndecodable);
    lagrange::header_t h;
    if (!transport::peekHeader(channel, data, size, h))
      return !transport::carriesHeader(channel) || refuse(channel, transport::RejectReason::kUndecodable);
    if (perTick(channel) && (h.tick < 0 || h.tick > last_tick_)) {
      ++not_recorded_[channel]["outside_run"];
      return false;
    }
    const auto refused = admission_.admit(channel, h, transport::HeaderAdmission::Order::kAcceptReordered);
    return !refused || refuse(channel, refused->reason);
  }

  /// Per channel and reason (summary.json log.not_recorded).
  const std::map<std::string, std::map<std::string, long long>>& notRecorded() const { return not_recorded_; }

 private:
  static bool perTick(const std::string& channel) {
    for (const transport::ChannelInfo& info : transport::kChannelTable)
      if (channel == info.name) return info.per_tick;
    return false;
  }

  bool refuse(const std::string& channel, transport::RejectReason why) {
    ++not_recorded_[channel][transport::reasonName(why)];
    return false;
  }

  transport::HeaderAdmission admission_;
  int64_t last_tick_;
  std::map<std::string, std::map<std::string, long long>> not_recorded_;
};

}  // namespace lagrange::logger
