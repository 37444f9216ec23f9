#pragma once
/// @file
/// The root of every error the project throws for a user to read, its two
/// kinds, and the exit codes of its commands and processes, in one place. It
/// sits in the lowest layer (util) so that every component can derive from it.

#include <stdexcept>
#include <string>

namespace lagrange {

/// What kind of failure an error reports; the exit code follows from it
/// (exitCodeOf), so a command never decides that on its own.
enum class ErrorKind {
  kBadInput,      ///< the user's config, flags, log, key or output path is wrong: nothing (more) was run
  kRuntimeFault,  ///< the run could not go on: a write, fork, LCM or a process failed, the plant stopped it
};

/// What went wrong, in words a user acts on (the key, the file, the value and
/// what was expected), and its kind. Throw BadInput or RuntimeFault, or a
/// component's own kind derived from them: config::ConfigError, tools::LogError,
/// tools::ReplayError, util::UnsafeOutputPath (bad input); plant::PlantStopped,
/// plant::PlantStalled, tools::PlotError, wiring::SimulationStopped (runtime faults). Code that must tell
/// a component's kind apart catches that kind.
///
/// The cores (model, controller, actuator, plant) also throw
/// std::invalid_argument when a caller breaks a documented precondition (a size,
/// a positive gain). config validates every value a user can write before a core
/// sees it, so such an exception reaching a command is a bug; it exits 1.
class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  ErrorKind kind() const noexcept { return kind_; }

 private:
  ErrorKind kind_;
};

/// Bad input: exit 2.
class BadInput : public Error {
 public:
  explicit BadInput(const std::string& what) : Error(ErrorKind::kBadInput, what) {}
};

/// A fault at run time: exit 1.
class RuntimeFault : public Error {
 public:
  explicit RuntimeFault(const std::string& what) : Error(ErrorKind::kRuntimeFault, what) {}
};

/// Exit codes of `lagrange` and of the processes (docs/reliability.md, "Errors and exit codes").
enum ExitCode : int {
  kExitOk = 0,
  kExitFailed = 1,    ///< the run failed (a process died, the plant stopped it), a condition or replay failed
  kExitBadInput = 2,  ///< bad config, flags, log or file: nothing (more) was run
  kExitMetricMissed = 3,  ///< `run --check`: the run completed but missed its stated metric
  kExitInterrupted = 130  ///< stopped by SIGINT / SIGTERM
};

/// The exit code of a command or process that stopped on `e`: 2 for bad input,
/// 1 for a runtime fault and for anything that is not a lagrange::Error (a
/// bug, or the system out of memory). The one place this mapping is made.
inline ExitCode exitCodeOf(const std::exception& e) noexcept {
  const auto* error = dynamic_cast<const Error*>(&e);
  return error != nullptr && error->kind() == ErrorKind::kBadInput ? kExitBadInput : kExitFailed;
}

}  // namespace lagrange
