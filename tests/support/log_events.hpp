#pragma once
/// @file
/// Crafting logs from recorded ones: every event of a log read into memory
/// (LCM's own log API), edited -- a message changed and sealed again, an
/// event dropped, bits flipped -- and written back with LCM's writer, which
/// numbers the events afresh. Each event's byte offset in the written log is
/// known, so a test can demand that an error names it.

#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "lagrange/scenario_t.hpp"
#include "transport/checksum.hpp"
#include "transport/safe_decode.hpp"

namespace lagrange::testing {

struct LoggedEvent {
  std::string channel;
  std::string data;
  int64_t timestamp = 0;
};

inline std::vector<LoggedEvent> readEvents(const std::string& path) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("cannot open " + path);
  std::vector<LoggedEvent> out;
  while (const lcm::LogEvent* ev = log.readNextEvent())
    out.push_back({ev->channel,
                   std::string(static_cast<const char*>(ev->data), static_cast<size_t>(ev->datalen)),
                   ev->timestamp});
  return out;
}

inline void writeEvents(const std::string& path, const std::vector<LoggedEvent>& events) {
  lcm::LogFile log(path, "w");
  if (!log.good()) throw std::runtime_error("cannot create " + path);
  for (const LoggedEvent& e : events) {
    lcm::LogEvent ev{};
    ev.timestamp = e.timestamp;
    ev.channel = e.channel;
    ev.datalen = static_cast<int32_t>(e.data.size());
    ev.data = const_cast<char*>(e.data.data());
    if (log.writeEvent(&ev) != 0) throw std::runtime_error("cannot write " + path);
  }
}

/// Byte offset of event `index` in a log `writeEvents` wrote (the LCM log
/// format: a 28-byte header, the channel, the data).
inline long long offsetOf(const std::vector<LoggedEvent>& events, size_t index) {
  long long offset = 0;
  for (size_t i = 0; i < index; ++i)
    offset += 28 + static_cast<long long>(events[i].channel.size() + events[i].data.size());
  return offset;
}

template <class Msg>
Msg decodeAs(const LoggedEvent& e) {
  Msg m;
  if (!transport::safeDecode(e.data.data(), e.data.size(), m))
    throw std::runtime_error("an event on " + e.channel + " does not decode");
  return m;
}

/// `m` as the event's data, sealed (transport/checksum.hpp): a message a
/// publisher with the run's key could have sent, intact.
template <class Msg>
void encodeSealed(LoggedEvent& e, Msg m) {
  transport::seal(m);
  e.data.assign(static_cast<size_t>(m.getEncodedSize()), '\0');
  m.encode(e.data.data(), 0, static_cast<int>(e.data.size()));
}

/// Index of the first event on `channel` whose header names `tick`.
template <class Msg>
size_t indexOf(const std::vector<LoggedEvent>& events, const std::string& channel, int64_t tick) {
  for (size_t i = 0; i < events.size(); ++i)
    if (events[i].channel == channel && decodeAs<Msg>(events[i]).header.tick == tick) return i;
  throw std::runtime_error("no " + channel + " tick " + std::to_string(tick));
}

}  // namespace lagrange::testing
