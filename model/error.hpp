#pragma once
/// @file
/// The root of every error the project throws for a user to read, and the exit
/// codes of its commands and processes, in one place. It sits in the lowest
/// layer so that every component can derive from it.

#include <stdexcept>

namespace lagrange {

/// What went wrong, in words a user acts on (the key, the file, the value and
/// what was expected). Each component derives its own kind: config::ConfigError,
/// plant::PlantStopped (the simulation failed or a user's limit was crossed),
/// tools::LogError, tools::ReplayError, tools::PlotError. Code that must tell a
/// kind apart catches that kind; anything else that escapes is a bug, reported
/// as such.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Exit codes of `lagrange` and of the processes (README, "Exit codes").
enum ExitCode : int {
  kExitOk = 0,
  kExitFailed = 1,    ///< the run failed (a process died, the plant stopped it), a condition or replay failed
  kExitBadInput = 2,  ///< bad config, flags, log or file: nothing (more) was run
  kExitMetricMissed = 3,  ///< `run --check`: the run completed but missed its stated metric
  kExitInterrupted = 130  ///< stopped by SIGINT / SIGTERM
};

}  // namespace lagrange
