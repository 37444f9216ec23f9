#pragma once
/// @file
/// The one reader of LCM log files in the project's commands: replay,
/// report, view and compare read every log through it (logs/log_reader.hpp
/// wraps it in readLog). It follows the LCM log format (every field
/// big-endian):
///
///     sync word 0xEDA1DA01 | event number int64 | timestamp int64 |
///     channel length int32 | data length int32 | channel | data
///
/// and, unlike LCM's own lcm_eventlog_read_next_event (which allocates
/// whatever a length field says: 0x7fffffff crashed it), checks both lengths
/// against a sane limit and against the bytes left in the file before it
/// allocates anything. What it meets where an event should start:
///
/// - a whole event: returned;
/// - a header whose lengths no LCM log can hold (negative, a channel name
///   longer than 999 bytes, data larger than LCM's largest message): the
///   log is malformed, LogError names the file, the byte offset and what was
///   expected;
/// - the sync word missing (a corrupt stretch): skipped up to the next sync
///   word that starts a whole, sane event, and counted (LogScan::skipped_bytes);
/// - an event that runs past the end of the file (a logger killed while
///   writing): the end; the log reads up to its last whole event, and the
///   rest is counted (LogScan::unreadable_tail_bytes);
/// - a whole event larger than its channel's messages can be in this log
///   (logs/event_bounds.hpp): skipped without reading its data, and named
///   (LogScan::oversized), so that nothing ever decodes it;
/// - a per-tick event for a tick outside the log's scenario's [0, last tick]
///   (a tick of 10^15 in a 1 s log; three million ticks for a thousand):
///   dropped and counted (LogScan::outside_run), so that what a reader keeps
///   is bounded by the scenario, not by the file.
///
/// The file is opened without blocking and refused unless it is a regular
/// file (util/input_file.hpp): a FIFO, /dev/zero or a directory is named and
/// refused before a byte is read.

#include <cstdint>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>
#include <vector>

#include "logs/event_bounds.hpp"
#include "util/error.hpp"

namespace lagrange::logs {

/// A file that is not an LCM log at all, is malformed, or cannot be opened.
class LogError : public lagrange::BadInput {
 public:
  using lagrange::BadInput::BadInput;
};

/// The LCM log format's constants, and the limits this reader holds a header to.
namespace log_format {
constexpr uint32_t kSyncWord = 0xEDA1DA01u;
constexpr long long kHeaderBytes = 4 + 8 + 8 + 4 + 4;
/// LCM's own log reader accepts channel names shorter than 1000 bytes (and
/// LCM publishes at most 63): longer is not a channel name but damage.
constexpr int32_t kMaxChannelBytes = 999;
/// LCM_MAX_MESSAGE_SIZE (lcm.h): no LCM message, hence no logged event, is larger.
constexpr int32_t kMaxDataBytes = 1 << 28;
}  // namespace log_format

/// A whole event skipped unread: larger than its channel's messages can be.
struct OversizedEvent {
  std::string channel;
  long long offset = 0;  ///< of the event in the file [bytes]
  long long bytes = 0;   ///< its data
  long long bound = 0;   ///< the most its channel's data can be in this log
  long long tick = -1;   ///< the tick its header claims (per-tick channels), -1: not read
};

/// What a pass over a log read.
struct LogScan {
  long long events = 0;                         ///< events read whole
  long long skipped_bytes = 0;                  ///< corrupt bytes between events, jumped over
  long long first_skipped_at = -1;              ///< byte offset of the first corrupt stretch, -1: none
  long long unreadable_tail_bytes = 0;          ///< bytes after the last whole event
  std::map<std::string, long long> channels;    ///< events per channel (oversized ones not counted)
  long long oversized_events = 0;               ///< whole events skipped unread: over their bound
  long long oversized_bytes = 0;                ///< their bytes, headers and channels included
  std::vector<OversizedEvent> first_oversized;  ///< the first few of them, for the warning
  std::string bounds_origin;                    ///< whose shape bounded the events (EventBounds::origin)
  long long outside_run = 0;                    ///< per-tick events for a tick outside the run, dropped
  long long outside_run_bytes = 0;              ///< their bytes, headers and channels included
  std::vector<OversizedEvent>
      first_outside;  ///< the first few of them (bytes: their data; bound: the last tick)

  /// Warnings for a person, empty when the log was read whole.
  std::vector<std::string> problems() const;
  /// "N events on CH1, CH2, ..." (at most a few channel names).
  std::string describe() const;
};

/// Reads a log's events in file order, checking each before it allocates.
class LogEventReader {
 public:
  /// Opens the log at `path`, without blocking and without reading it.
  /// @throws LogError naming the file if it cannot be opened or is not a
  /// regular file (a directory, a FIFO, a device).
  explicit LogEventReader(const std::string& path);
  /// Reads `size` bytes of an open stream (not closed here), named `name` in
  /// messages: a log in memory (fmemopen) for the fuzzer and the unit tests.
  LogEventReader(std::FILE* file, long long size, std::string name);
  ~LogEventReader();
  LogEventReader(const LogEventReader&) = delete;
  LogEventReader& operator=(const LogEventReader&) = delete;

  /// The next whole event (valid until the next call), or nullptr at the end.
  /// @throws LogError naming the file, the event's byte offset and what was
  /// expected, if the event there is malformed, or if the end comes without
  /// a single event in a file that is not empty (not an LCM log).
  const lcm::LogEvent* next();

  /// What has been read so far (complete once next() returned nullptr).
  const LogScan& scan() const { return scan_; }

  /// From the next event on, an event whose data is larger than `bounds`
  /// allow for its channel is skipped unread and counted in the scan. By
  /// default the project's limits bound every event (EventBounds::projectLimits).
  void limitEvents(EventBounds bounds);
  /// From the next event on, hands out only the events on `channel`: the
  /// others are passed over without reading their data (and counted as
  /// events). For a reader that looks for one channel, e.g. the SCENARIO.
  void readOnly(std::string channel) { only_channel_ = std::move(channel); }

 private:
  // What stands at an offset where an event should start.
  enum class Found { kEvent, kNoSyncWord, kCutShort, kMalformed };
  struct Header {
    int32_t channel_bytes = 0, data_bytes = 0;
    int64_t event_number = 0, timestamp = 0;
  };
  Found inspect(long long offset, Header& header, std::string& problem);
  long long nextEventStart(long long from);
  bool readAt(long long offset, void* into, std::size_t bytes);
  void finish();

  std::FILE* file_ = nullptr;
  bool owned_ = false;
  long long size_ = 0;
  std::string name_;
  long long position_ = 0;  // where the next event should start
  bool done_ = false;
  LogScan scan_;
  EventBounds bounds_ = EventBounds::projectLimits();
  std::string only_channel_;  // "": every channel
  void skipOversized(long long offset, const std::string& channel, long long bytes, long long bound);
  lcm::LogEvent event_{};
  std::vector<char> data_;
};

}  // namespace lagrange::logs
