#pragma once
/// @file
/// What of a log replay could not use, and where, so that a message the log
/// lacks is named with what may have held it: a copy that fails its
/// checksum (a bit flipped after it was sealed: LCM logs have no checksum of
/// their own, every lagrange message has one), an event that does not
/// decode, an event whose channel name is one byte from a channel of this
/// project (a damaged name), corrupt bytes the reader skipped.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace lagrange::tools::replay_log {

/// An event replay could not use, on (or meant for) one of the per-tick channels.
struct DamagedEvent {
  std::string channel;          ///< the channel it is, or was meant to be, on
  long long offset = 0;         ///< byte offset of the event in the log
  std::optional<int64_t> tick;  ///< the tick its (damaged) header names, when it decodes
  std::string why;              ///< "fails its checksum ...", "does not decode as ...", ...
};

/// Corrupt bytes between events the reader jumped over (logs/log_event_reader.hpp).
struct SkippedStretch {
  long long offset = 0, bytes = 0;
};

struct LogDamage {
  std::vector<DamagedEvent> events;  ///< in log order
  std::vector<SkippedStretch> skipped;
};

/// The per-tick channel of this project `name` is one changed byte away
/// from, or "" (for any other name, and for the channel names themselves).
std::string channelOneByteFrom(const std::string& name);

/// What may have held `channel` ticks `from`..`to`, which would lie between
/// byte offsets `lower` and `upper`: a damaged copy naming one of those ticks
/// anywhere, other damaged events (their tick may be what was damaged) and
/// skipped bytes in that stretch (at most three); "" when nothing.
std::string whatMayHaveHeld(const LogDamage& damage, const std::string& channel, int64_t from, int64_t to,
                            long long lower, long long upper);

/// "tick 5", or "ticks 5 to 7".
std::string tickRange(int64_t from, int64_t to);

/// A warning: how many events could not be used, on which channels, and the first.
std::string describe(const LogDamage& damage);

}  // namespace lagrange::tools::replay_log
