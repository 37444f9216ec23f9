#include "logs/log_event_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "transport/channels.hpp"
#include "transport/header_admission.hpp"
#include "util/input_file.hpp"

namespace lagrange::logs {

namespace {

using log_format::kHeaderBytes;
using log_format::kMaxChannelBytes;
using log_format::kMaxDataBytes;
using log_format::kSyncWord;

uint32_t bigEndian32(const unsigned char* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

uint64_t bigEndian64(const unsigned char* p) { return (uint64_t{bigEndian32(p)} << 32) | bigEndian32(p + 4); }

// As people read it in a hex dump of the file.
constexpr const char* kSyncWordText = "0xEDA1DA01";

// Oversized events named in the warning; the rest are counted.
constexpr std::size_t kOversizedNamed = 3;
// Events for a tick outside the run kept for a reader to name (replay: a
// damaged tick field may be what a gap lacks); the rest are counted.
constexpr std::size_t kOutsideKept = 16;

bool isPerTick(const std::string& channel) {
  for (const transport::ChannelInfo& info : transport::kChannelTable)
    if (channel == info.name) return info.per_tick;
  return false;
}

}  // namespace

std::vector<std::string> LogScan::problems() const {
  std::vector<std::string> out;
  if (skipped_bytes > 0)
    out.push_back(std::to_string(skipped_bytes) +
                  " corrupt bytes between events were skipped (the events there are lost; the first "
                  "stretch starts at byte " +
                  std::to_string(first_skipped_at) + ", where an event with the LCM sync word " +
                  kSyncWordText + " was expected)");
  if (unreadable_tail_bytes > 0)
    out.push_back("the log ends with " + std::to_string(unreadable_tail_bytes) +
                  " bytes that are not a whole event (cut short, e.g. a run killed while writing); " +
                  std::to_string(events) + " whole events before them were read");
  if (oversized_events > 0) {
    std::string named;
    for (const OversizedEvent& e : first_oversized)
      named += std::string(named.empty() ? "" : "; ") + e.channel + " at byte " + std::to_string(e.offset) +
               (e.tick >= 0 ? " (tick " + std::to_string(e.tick) + ")" : "") + ": " +
               std::to_string(e.bytes) + " bytes, at most " + std::to_string(e.bound) + " expected";
    out.push_back(std::to_string(oversized_events) + (oversized_events == 1 ? " event was" : " events were") +
                  " larger than its channel's messages can be and skipped unread, never decoded (" + named +
                  (oversized_events > static_cast<long long>(first_oversized.size()) ? "; ..." : "") +
                  "); the bound is the message with the counts of " + bounds_origin);
  }
  if (outside_run > 0)
    out.push_back(std::to_string(outside_run) + (outside_run == 1 ? " event" : " events") +
                  " for a tick outside the run were dropped (the first at byte " +
                  std::to_string(first_outside.front().offset) + ", tick " +
                  std::to_string(first_outside.front().tick) + "); the run's ticks are those of " +
                  bounds_origin);
  return out;
}

std::string LogScan::describe() const {
  std::string out = std::to_string(events) + " events";
  if (channels.empty()) return out;
  out += " on ";
  int shown = 0;
  for (const auto& [channel, n] : channels) {
    if (shown++ == 6) {
      out += ", ...";
      break;
    }
    out += (shown > 1 ? ", " : "") + channel;
  }
  return out;
}

LogEventReader::LogEventReader(const std::string& path) : owned_(true), name_(path) {
  util::InputFile input = util::InputFile::open(path, "an LCM log file");
  if (!input.ok()) throw LogError(input.error());
  size_ = input.size();
  file_ = fdopen(input.fd(), "rb");
  if (file_ == nullptr) throw LogError("cannot open '" + path + "': " + std::strerror(errno));
  input.release();  // the stream closes it now
  scan_.bounds_origin = bounds_.origin();
}

LogEventReader::LogEventReader(std::FILE* file, long long size, std::string name)
    : file_(file), size_(size), name_(std::move(name)) {
  scan_.bounds_origin = bounds_.origin();
}

void LogEventReader::limitEvents(EventBounds bounds) {
  bounds_ = std::move(bounds);
  scan_.bounds_origin = bounds_.origin();
}

void LogEventReader::skipOversized(long long offset, const std::string& channel, long long bytes,
                                   long long bound) {
  ++scan_.oversized_events;
  scan_.oversized_bytes += kHeaderBytes + static_cast<long long>(channel.size()) + bytes;
  if (scan_.first_oversized.size() >= kOversizedNamed) return;
  OversizedEvent e{channel, offset, bytes, bound, -1};
  // The tick its header claims, for the warning: after the 8-byte fingerprint (header_t.tick first).
  unsigned char tick[8];
  if (isPerTick(channel) && bytes >= 16 &&
      readAt(offset + kHeaderBytes + static_cast<long long>(channel.size()) + 8, tick, sizeof tick))
    e.tick = static_cast<long long>(bigEndian64(tick));
  scan_.first_oversized.push_back(std::move(e));
}

LogEventReader::~LogEventReader() {
  if (owned_ && file_ != nullptr) std::fclose(file_);
}

bool LogEventReader::readAt(long long offset, void* into, std::size_t bytes) {
  if (fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0) return false;
  return std::fread(into, 1, bytes, file_) == bytes;
}

// Only reads: nothing is allocated on the header's word until it has passed.
LogEventReader::Found LogEventReader::inspect(long long offset, Header& header, std::string& problem) {
  const long long left = size_ - offset;
  unsigned char bytes[kHeaderBytes];
  if (left < 4 || !readAt(offset, bytes, 4)) return Found::kCutShort;
  if (bigEndian32(bytes) != kSyncWord) return Found::kNoSyncWord;
  if (left < kHeaderBytes || !readAt(offset + 4, bytes + 4, kHeaderBytes - 4)) return Found::kCutShort;
  header.event_number = static_cast<int64_t>(bigEndian64(bytes + 4));
  header.timestamp = static_cast<int64_t>(bigEndian64(bytes + 12));
  header.channel_bytes = static_cast<int32_t>(bigEndian32(bytes + 20));
  header.data_bytes = static_cast<int32_t>(bigEndian32(bytes + 24));
  const std::string at = name_ + ": malformed LCM log: the event at byte " + std::to_string(offset);
  if (header.channel_bytes < 1 || header.channel_bytes > kMaxChannelBytes) {
    problem = at + " gives a channel name length of " + std::to_string(header.channel_bytes) +
              " bytes; expected 1 to " + std::to_string(kMaxChannelBytes);
    return Found::kMalformed;
  }
  if (header.data_bytes < 0 || header.data_bytes > kMaxDataBytes) {
    problem = at + " gives a data length of " + std::to_string(header.data_bytes) + " bytes; expected 0 to " +
              std::to_string(kMaxDataBytes) + " (LCM's largest message), and at most the " +
              std::to_string(std::max<long long>(0, left - kHeaderBytes - header.channel_bytes)) +
              " bytes left in the file after its header and channel";
    return Found::kMalformed;
  }
  if (kHeaderBytes + header.channel_bytes + header.data_bytes > left) return Found::kCutShort;
  return Found::kEvent;
}

// The first offset at or after `from` where a whole, sane event starts, or -1.
// A sync word whose header is not sane is a chance match inside the corrupt
// stretch (or payload bytes), not an event: the search goes on behind it.
long long LogEventReader::nextEventStart(long long from) {
  for (long long candidate = from; candidate + 4 <= size_;) {
    if (fseeko(file_, static_cast<off_t>(candidate), SEEK_SET) != 0) return -1;
    uint32_t window = 0;
    long long found = -1;
    long long offset = candidate;  // of the byte fgetc reads next
    for (int c; offset < size_ && (c = std::fgetc(file_)) != EOF; ++offset) {
      window = (window << 8) | static_cast<uint32_t>(c);
      if (offset - candidate >= 3 && window == kSyncWord) {
        found = offset - 3;
        break;
      }
    }
    if (found < 0) return -1;
    Header header;
    std::string problem;
    if (inspect(found, header, problem) == Found::kEvent) return found;
    candidate = found + 1;
  }
  return -1;
}

void LogEventReader::finish() {
  done_ = true;
  if (scan_.events == 0 && scan_.oversized_events == 0 && size_ > 0)
    throw LogError(name_ + " is not an LCM log: no event in its " + std::to_string(size_) +
                   " bytes (expected events starting with the LCM sync word " + kSyncWordText + ")");
}

const lcm::LogEvent* LogEventReader::next() {
  while (!done_) {
    if (position_ >= size_) {
      finish();
      break;
    }
    Header header;
    std::string problem;
    const Found found = inspect(position_, header, problem);
    if (found == Found::kMalformed) throw LogError(problem);
    if (found != Found::kEvent) {
      // No whole event here: corrupt bytes if one follows, else the end of a log cut short.
      const long long next = nextEventStart(position_ + 1);
      if (next < 0) {
        scan_.unreadable_tail_bytes = size_ - position_;
        finish();
        break;
      }
      if (scan_.first_skipped_at < 0) scan_.first_skipped_at = position_;
      scan_.skipped_bytes += next - position_;
      position_ = next;
      continue;
    }
    // Both lengths are sane and the file holds them: at most a file's bytes are allocated.
    event_.eventnum = header.event_number;
    event_.timestamp = header.timestamp;
    event_.channel.assign(static_cast<std::size_t>(header.channel_bytes), '\0');
    if (!readAt(position_ + kHeaderBytes, event_.channel.data(), event_.channel.size()))
      throw LogError("cannot read " + name_ + " at byte " + std::to_string(position_) + ": " +
                     std::strerror(errno));
    const long long event_start = position_;
    position_ += kHeaderBytes + header.channel_bytes + header.data_bytes;
    if (!only_channel_.empty() && event_.channel != only_channel_) {
      ++scan_.events;
      ++scan_.channels[event_.channel];
      continue;
    }
    // Larger than its channel's messages can be: not one of them, and never read.
    const long long bound = bounds_.largestData(event_.channel);
    if (bound >= 0 && header.data_bytes > bound) {
      skipOversized(event_start, event_.channel, header.data_bytes, bound);
      continue;
    }
    data_.resize(static_cast<std::size_t>(header.data_bytes) + 1);  // + 1: never a zero-size buffer
    if (!readAt(event_start + kHeaderBytes + header.channel_bytes, data_.data(),
                static_cast<std::size_t>(header.data_bytes)))
      throw LogError("cannot read " + name_ + " at byte " + std::to_string(event_start) + ": " +
                     std::strerror(errno));
    // A tick the run never had: no message of the run, and never kept.
    if (lagrange::header_t h;
        isPerTick(event_.channel) &&
        transport::peekHeader(event_.channel, data_.data(), static_cast<std::size_t>(header.data_bytes), h) &&
        (h.tick < 0 || h.tick > bounds_.lastTick())) {
      ++scan_.outside_run;
      scan_.outside_run_bytes += kHeaderBytes + header.channel_bytes + header.data_bytes;
      if (scan_.first_outside.size() < kOutsideKept)
        scan_.first_outside.push_back(
            {event_.channel, event_start, header.data_bytes, bounds_.lastTick(), h.tick});
      continue;
    }
    event_.datalen = header.data_bytes;
    event_.data = data_.data();
    ++scan_.events;
    ++scan_.channels[event_.channel];
    return &event_;
  }
  return nullptr;
}

}  // namespace lagrange::logs
