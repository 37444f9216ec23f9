#pragma once
/// @file
/// Reading an LCM log event by event (logs/log_event_reader.hpp: every
/// length checked before anything is allocated), noticing what LCM's own
/// reader does not say: bytes skipped (a corrupt stretch; reading resumes at
/// the next whole event) and bytes at the end that are not a whole event (a
/// log cut short, e.g. a run killed while writing). Replay, report, view and
/// compare all read logs through this, so all name what was read and what was not.

#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "logs/log_event_reader.hpp"
#include "transport/checksum.hpp"
#include "transport/lcm_node.hpp"
#include "transport/safe_decode.hpp"

namespace lagrange::logs {

/// Calls on_event for every event of the log at `path`, in file order, but
/// those larger than their channel's messages can be in this log (boundsOfLog):
/// each is skipped unread and named in the scan's problems().
/// @throws LogError if the file cannot be opened or is not a regular file,
/// holds no event in a nonzero length, holds a malformed event (named with
/// its byte offset), or a SCENARIO larger than any scenario can be.
LogScan readLog(const std::string& path, const std::function<void(const lcm::LogEvent&)>& on_event);

/// How large each channel's events can be in the log at `path`: its per-tick
/// messages have the counts its first SCENARIO that decodes gives (joints,
/// actuator order, torque steps a tick); without one, or with one that is not
/// a valid scenario, the project's limits (logs/event_bounds.hpp). Reads the
/// events' headers up to that SCENARIO, and no other event's data.
/// @throws LogError as readLog, and when the first SCENARIO is larger than
/// any scenario can be (named with its byte offset, its size and the bound).
EventBounds boundsOfLog(const std::string& path);

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

/// decodeIntact of the bytes, or of all but their last kMacBytes: a message
/// recorded or heard off a run's wire by a program without the run's key (a
/// stock lcm-logger) still carries its MAC trailer (transport/message_auth.hpp),
/// which only the key could check. lagrange's own logger checks it and
/// records the message without it.
template <class Msg>
bool decodeSkippingTrailer(const void* data, std::size_t size, Msg& m) {
  return decodeIntact(data, size, m) ||
         (size > transport::kMacBytes && decodeIntact(data, size - transport::kMacBytes, m));
}

/// decodeSkippingTrailer of a log event's bytes.
template <class Msg>
bool decodeEvent(const lcm::LogEvent& ev, Msg& m) {
  return ev.datalen >= 0 && decodeSkippingTrailer(ev.data, static_cast<std::size_t>(ev.datalen), m);
}

/// The scenario YAML of a SCENARIO event (scenario_t), or nothing if it is not one.
std::optional<std::string> scenarioYaml(const lcm::LogEvent& ev);

}  // namespace lagrange::logs
