#include "tools/log_reader.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "lagrange/scenario_t.hpp"

namespace lagrange::tools {

namespace {
// Bytes of an event on disk: sync word, event number, timestamp, the two
// lengths, then channel and data (LCM log format).
constexpr long long kEventHeaderBytes = 4 + 8 + 8 + 4 + 4;

// Offset of the next event sync word (0xEDA1DA01, big-endian) at or after
// `from`, or -1. LCM's reader gives up at a header it cannot parse; this is
// how reading resumes behind a corrupt stretch instead of losing the rest.
long long nextSyncWord(std::FILE* f, long long from) {
  if (std::fseek(f, from, SEEK_SET) != 0) return -1;
  uint32_t window = 0;
  long long offset = from;
  for (int c; (c = std::fgetc(f)) != EOF; ++offset) {
    window = (window << 8) | static_cast<uint32_t>(c);
    if (offset - from >= 3 && window == 0xEDA1DA01u) return offset - 3;
  }
  return -1;
}
}  // namespace

std::vector<std::string> LogScan::problems() const {
  std::vector<std::string> out;
  if (skipped_bytes > 0)
    out.push_back(std::to_string(skipped_bytes) +
                  " corrupt bytes between events were skipped (the events there are lost)");
  if (unreadable_tail_bytes > 0)
    out.push_back("the log ends with " + std::to_string(unreadable_tail_bytes) +
                  " bytes that are not a whole event (cut short, e.g. a run killed while writing); " +
                  std::to_string(events) + " whole events before them were read");
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

std::optional<std::string> scenarioYaml(const lcm::LogEvent& ev) {
  lagrange::scenario_t m;
  if (!decodeEvent(ev, m)) return std::nullopt;
  return m.yaml;
}

LogScan readLog(const std::string& path, const std::function<void(const lcm::LogEvent&)>& on_event) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw LogError("cannot read " + path + ": " + ec.message());
  lcm::LogFile log(path, "r");
  if (!log.good()) throw LogError("cannot open " + path + " as an LCM log");
  LogScan scan;
  long long position = 0;  // end of the last whole event
  for (;;) {
    const lcm::LogEvent* ev = log.readNextEvent();
    if (ev == nullptr) {
      const long long next = nextSyncWord(log.getFilePtr(), position + 1);
      if (next < 0) break;
      scan.skipped_bytes += next - position;
      position = next;
      std::fseek(log.getFilePtr(), next, SEEK_SET);
      continue;
    }
    const long long end = std::ftell(log.getFilePtr());
    const long long expected = kEventHeaderBytes + static_cast<long long>(ev->channel.size()) + ev->datalen;
    scan.skipped_bytes += end - position - expected;
    position = end;
    ++scan.events;
    ++scan.channels[ev->channel];
    on_event(*ev);
  }
  scan.unreadable_tail_bytes = static_cast<long long>(size) - position;
  if (scan.events == 0 && size > 0)
    throw LogError(path + " is not an LCM log: no event in its " + std::to_string(size) +
                   " bytes (expected events starting with the LCM sync word 0xEDA1DA01)");
  return scan;
}

}  // namespace lagrange::tools
