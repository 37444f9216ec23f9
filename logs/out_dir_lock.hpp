#pragma once
/// @file
/// One writer per output directory. Two runs with the same --out wrote one
/// interleaved, corrupt run.lcm and both exited 0; now the launcher holds a
/// lock on DIR/.lagrange.lock for the whole run (its processes write into
/// DIR under it), and a second launcher is refused with the holder's pid.
///
/// A POSIX record lock (fcntl F_SETLK): the kernel drops it when its holder
/// exits, however it ends (also SIGKILL), so a killed run leaves no stale
/// lock; and F_GETLK names the holder's pid, so the refusal can say who. The
/// lock is not inherited by fork(), so it stays the launcher's. (It is also
/// dropped if this process closes any descriptor of the lock file: nothing
/// else opens it.)

#include <string>

namespace lagrange::logs {

class OutDirLock {
 public:
  /// Locks `dir` (an existing directory) for `who` (e.g. "lagrange run").
  /// Throws lagrange::BadInput (exit 2) naming the directory and the
  /// holder's pid when another process holds it, or when the lock file is a
  /// link planted there; RuntimeFault when it cannot be created.
  OutDirLock(const std::string& dir, const std::string& who);
  ~OutDirLock();
  OutDirLock(const OutDirLock&) = delete;
  OutDirLock& operator=(const OutDirLock&) = delete;

  static constexpr const char* kFileName = ".lagrange.lock";

 private:
  int fd_ = -1;
};

}  // namespace lagrange::logs
