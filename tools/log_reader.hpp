#pragma once
/// @file
/// Reading an LCM log event by event through lcm::LogFile, noticing what it
/// does not say: bytes it skipped (a corrupt stretch, the reader resyncs on
/// the next event marker) and bytes at the end it could not read (a log cut
/// short, e.g. a run killed while writing). Replay and report both read
/// logs through this, so both name what was read and what was not.

#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "model/error.hpp"
#include "transport/checksum.hpp"
#include "transport/lcm_node.hpp"
#include "transport/safe_decode.hpp"

namespace lagrange::tools {

/// A file that is not an LCM log at all, or cannot be opened.
class LogError : public lagrange::Error {
 public:
  using lagrange::Error::Error;
};

/// What a pass over a log read.
struct LogScan {
  long long events = 0;                       ///< events read whole
  long long skipped_bytes = 0;                ///< corrupt bytes between events, jumped over
  long long unreadable_tail_bytes = 0;        ///< bytes after the last whole event
  std::map<std::string, long long> channels;  ///< events per channel

  /// Warnings for a person, empty when the log was read whole.
  std::vector<std::string> problems() const;
  /// "N events on CH1, CH2, ..." (at most a few channel names).
  std::string describe() const;
};

/// Calls on_event for every event of the log at `path`, in file order.
/// @throws LogError if the file cannot be opened or holds no event in a nonzero length.
LogScan readLog(const std::string& path, const std::function<void(const lcm::LogEvent&)>& on_event);

/// Decodes an event as Msg; false (never a throw, never a huge allocation)
/// if it is not one whole, intact Msg: a message whose checksum does not
/// match was corrupted on the way (a log records what arrived; the intact
/// copy, re-sent, follows). Unsealed messages (checksum 0: in-process runs) pass.
template <class Msg>
bool decodeIntact(const void* data, std::size_t size, Msg& m) {
  if (!transport::safeDecode(data, size, m)) return false;
  if constexpr (transport::HasHeader<Msg>::value) return m.header.checksum == 0 || transport::intact(m);
  return true;
}

/// decodeIntact of a log event's bytes.
template <class Msg>
bool decodeEvent(const lcm::LogEvent& ev, Msg& m) {
  return ev.datalen >= 0 && decodeIntact(ev.data, static_cast<std::size_t>(ev.datalen), m);
}

/// The scenario YAML of a SCENARIO event (scenario_t), or nothing if it is not one.
std::optional<std::string> scenarioYaml(const lcm::LogEvent& ev);

}  // namespace lagrange::tools
