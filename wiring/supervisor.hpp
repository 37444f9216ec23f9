#pragma once
/// @file
/// Starts the processes of a run and watches them: who is alive, who died and how.

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace lagrange::wiring {

struct ChildSpec {
  std::string name;               ///< "plant", ...
  std::vector<std::string> argv;  ///< argv[0]: the executable, a path or a name on PATH
  std::vector<std::string> env;   ///< NAME=VALUE added to the environment
  std::string working_directory;  ///< where it starts; empty: the launcher's
  std::string log_path;           ///< stdout and stderr go here
  int pass_fd = -1;               ///< if >= 0, handed to the child as its file descriptor 3
  bool append_log = false;        ///< append to log_path (a restart) instead of truncating it
  /// A program from outside in a realtime run (issue #46): the scheduling the
  /// built-in processes give themselves, set in the child before its exec
  /// (exec keeps both): SCHED_FIFO at this priority (0: the normal
  /// scheduler) and these CPUs (empty: any). What the kernel refuses is
  /// said in its log, and the program runs as it can.
  int fifo_priority = 0;
  std::vector<int> cpus;
};

/// How `pid` is scheduled, as the loops report it: "fifo:50", "other", with
/// " cpus 1" when it is pinned to fewer than every CPU.
std::string schedulerOf(pid_t pid);

struct ChildExit {
  std::string name;
  int exit_code = 0;        ///< valid when signal == 0
  int signal = 0;           ///< the signal that killed it, or 0
  double cpu_user = 0.0;    ///< CPU time in user mode [s]
  double cpu_system = 0.0;  ///< CPU time in the kernel [s]
  bool failed() const { return signal != 0 || exit_code != 0; }
  std::string describe() const;  ///< "exited with code 3" / "was killed by signal 9 (Killed)"
};

class Supervisor {
 public:
  ~Supervisor();  ///< kills whatever is still running

  /// @throws RuntimeFault if fork or exec setup fails.
  void start(const ChildSpec& spec);

  /// Starts the named child again (it must have exited), appending to its log.
  /// @throws std::logic_error if there is no such child, or it still runs.
  void restart(const std::string& name);

  /// Sends `sig` to the named child if it runs; false if it does not.
  bool signal(const std::string& name, int sig);

  /// Children that exited since the last call (non-blocking).
  std::vector<ChildExit> reap();

  bool anyRunning() const;
  /// The running child's pid, or -1.
  pid_t pidOf(const std::string& name) const;

  /// SIGTERM to every running child, then SIGKILL after `grace_seconds`.
  /// Returns how they exited.
  std::vector<ChildExit> stopAll(double grace_seconds);

  /// Wait (polling reap) until all exit or timeout; returns their exits.
  std::vector<ChildExit> waitAll(double timeout_seconds);

 private:
  struct Child {
    ChildSpec spec;
    pid_t pid = -1;
    bool running = false;
  };
  std::vector<Child> children_;
};

}  // namespace lagrange::wiring
