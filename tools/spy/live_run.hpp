#pragma once
/// @file
/// `lagrange spy DIR` waits for a live run in DIR: the folder may not exist
/// yet, hold no lcm.json yet, or hold one of a run that has ended (a new run
/// into the same folder replaces it). What DIR holds now is a LiveRunProbe;
/// waitForLiveRun polls it until a run is going there, or says why not.

#include <functional>
#include <string>

#include "tools/spy/spy.hpp"

namespace lagrange::tools {

struct LiveRunProbe {
  enum class State {
    kMissing,     ///< DIR does not exist
    kNotAFolder,  ///< DIR is something else than a directory
    kNoEndpoint,  ///< DIR has no lcm.json (yet: a run writes it as it starts; an inproc run never)
    kRefused,     ///< lcm.json is not what `lagrange run` writes (or is being written)
    kEnded,       ///< lcm.json names a launcher that is gone
    kLive,        ///< a run is going: `endpoint` is its
  };
  State state = State::kMissing;
  RunEndpoint endpoint;
  std::string problem;  ///< kRefused: readEndpoint's reason
};

/// What `dir` holds now. Never throws for what a folder holds.
LiveRunProbe probeLiveRun(const std::string& dir);

/// Why `probe` is not a live run in `dir`, as the error says it (what was
/// found, what was expected, how to start one).
std::string notLiveText(const std::string& dir, const LiveRunProbe& probe);

/// Polls `dir` until a run is going there, for at most `seconds` (0: looks
/// once). Before the first wait calls `before_waiting` (which may throw:
/// nothing to wait for) and says on `say` that it waits and how to start a
/// run. A refused lcm.json is looked at again for 2 s (it may be half
/// written), then refused.
/// @throws BadInput naming what DIR holds when no run is going there in time.
RunEndpoint waitForLiveRun(const std::string& dir, double seconds, std::ostream& say,
                           const std::function<void()>& before_waiting);

}  // namespace lagrange::tools
