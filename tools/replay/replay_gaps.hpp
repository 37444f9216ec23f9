#pragma once
/// @file
/// Telling a log with a hole in it from a component that computed something
/// else. A component's state (a filter, a chain, the arm) advances with every
/// output it computes, so a replay that skipped one output the log lacks
/// would differ from the next recorded output on -- and say DIVERGED of a
/// component that did nothing wrong. So before each recorded output is
/// compared, replay checks that none is missing between it and the one
/// before, and names a gap as a gap: the ticks, or how many messages, and
/// what the log says of them (a corrupt copy, bytes skipped).

#include "lagrange/header_t.hpp"
#include "tools/replay/replay_log.hpp"

namespace lagrange::tools::replay_log {

/// How a component's outputs follow each other in a log.
enum class OutputSequence {
  kEveryTick,       ///< one per tick from tick 0: the plant, and every component in lockstep or in process
  kSequenceNumber,  ///< realtime controller and actuator: they skip a sample with no fresh input, and
                    ///< number every message they publish (header.seq: 1, 2, ... per publisher)
};

/// The sequence `channel`'s outputs follow in a log of `mode`.
OutputSequence outputSequence(const std::string& channel, config::Mode mode);

/// Checks that `next`, the recorded output of `channel` replay is about to
/// compare, follows `previous` (nullptr: `next` is the first) with nothing
/// between them missing from the log. `replayed`: outputs already compared.
/// @throws ReplayError (bad input) naming the gap (or an output out of
/// sequence), what the log says of it and what was replayed before it.
void requireNoGap(const Recorded& rec, const std::string& channel, OutputSequence sequence,
                  const lagrange::header_t* previous, const lagrange::header_t& next, long long replayed);

}  // namespace lagrange::tools::replay_log
