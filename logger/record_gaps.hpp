#pragma once
/// @file
/// Which messages of the run the log lacks, per channel: what a realtime run
/// could not record (summary.json log.missing_records, log.complete).
///
/// Every publisher numbers its messages on each channel 1, 2, 3, ...
/// (header.seq, retransmissions included), so a number the log never got is
/// a message missing from it -- lost on the way, or arriving while the
/// logger was not reading (stopped, overloaded) and its socket buffer
/// overflowed. Gaps are counted up to the newest number recorded; after it,
/// the publisher's last STATUS tells how many it published (not for STATUS
/// itself: only its gaps after the first recorded count). A restarted
/// process is a new publisher (its pid): the messages of its earlier life
/// after its last recorded one are not counted (no STATUS of it remains).

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "lagrange/status_t.hpp"
#include "transport/channels.hpp"
#include "transport/checksum.hpp"
#include "transport/safe_decode.hpp"

namespace lagrange::logger {

class RecordGaps {
 public:
  /// A recorded datagram: counted when it is an intact message of this run
  /// (`run_id`; 0: any) from another process than the logger; others (other
  /// runs, corrupt bytes, other channels) have no place in the numbering.
  void recorded(const std::string& channel, const void* data, size_t size, int64_t run_id) {
    if (channel == transport::kStatus) {
      lagrange::status_t m;
      if (transport::safeDecode(data, size, m)) note(channel, m.header, run_id, intactOrUnsealed(m));
      return;
    }
    transport::withChannelMessage(channel, false, [&](auto type) {
      if (transport::safeDecode(data, size, type)) note(channel, type.header, run_id, intactOrUnsealed(type));
      return true;
    });
  }

  /// Per channel: the messages of each publisher the log lacks. `last_status`:
  /// the newest STATUS of each process (its counters say what it published).
  /// Every channel a process published or the log holds has an entry, 0 when
  /// none is missing.
  std::map<std::string, long long> missing(
      const std::map<std::string, lagrange::status_t>& last_status) const {
    std::map<std::string, long long> out;
    for (const auto& [key, numbers] : sources_) {
      const auto& [channel, publisher, pid] = key;
      // Gaps up to the newest recorded. STATUS from the oldest recorded
      // only: a process says "ready" as it starts, maybe before the logger
      // listens (the per-tick channels start only once the logger is ready).
      const bool status = channel == transport::kStatus;
      long long lacking = numbers.newest - (status ? numbers.oldest - 1 : 0) - numbers.distinct;
      // Published after the newest recorded. Not for STATUS: a process's
      // STATUS counts itself, and its final ones go out after the logger
      // has stopped listening -- the end of the run, not a loss.
      if (const int64_t published = publishedBy(last_status, channel, publisher, pid);
          !status && published > numbers.newest)
        lacking += published - numbers.newest;
      out[channel] += lacking;
    }
    // A channel of which the log holds nothing at all from its publisher.
    for (const auto& [process, st] : last_status) {
      if (process == "logger") continue;
      for (const auto& c : st.channels) {
        long long& lacking = out[c.channel];
        if (sources_.count({c.channel, process, st.header.publisher_pid}) == 0 &&
            c.channel != transport::kStatus)
          lacking += c.published;
      }
    }
    return out;
  }

 private:
  // A sequence number beyond this is no honest run's (an hour at 1 kHz is
  // 3.6e6): ignored rather than allocated for.
  static constexpr int64_t kMaxSeq = int64_t{1} << 27;

  struct Numbers {
    std::vector<bool> seen;  ///< by sequence number
    long long distinct = 0;  ///< numbers recorded (a duplicate counts once)
    int64_t newest = 0;      ///< the largest recorded
    int64_t oldest = 0;      ///< the smallest recorded
  };
  using Source = std::tuple<std::string, std::string, int32_t>;  ///< channel, publisher, pid

  template <class Msg>
  static bool intactOrUnsealed(const Msg& m) {
    return m.header.checksum == 0 || transport::intact(m);
  }

  void note(const std::string& channel, const lagrange::header_t& h, int64_t run_id, bool intact) {
    if (!intact || (run_id != 0 && h.run_id != run_id) || h.publisher == "logger") return;
    if (h.seq <= 0 || h.seq > kMaxSeq) return;
    Numbers& n = sources_[{channel, h.publisher, h.publisher_pid}];
    const auto i = static_cast<size_t>(h.seq);
    if (n.seen.size() <= i) n.seen.resize(std::max(i + 1, n.seen.size() * 2));
    if (n.seen[i]) return;
    n.seen[i] = true;
    ++n.distinct;
    n.newest = std::max(n.newest, h.seq);
    n.oldest = n.distinct == 1 ? h.seq : std::min(n.oldest, h.seq);
  }

  static int64_t publishedBy(const std::map<std::string, lagrange::status_t>& last_status,
                             const std::string& channel, const std::string& publisher, int32_t pid) {
    const auto it = last_status.find(publisher);
    if (it == last_status.end() || it->second.header.publisher_pid != pid) return 0;
    for (const auto& c : it->second.channels)
      if (c.channel == channel) return c.published;
    return 0;
  }

  std::map<Source, Numbers> sources_;
};

}  // namespace lagrange::logger
