#pragma once
/// @file
/// Starting a helper process whose stdout and stderr go to a log file: what
/// `lagrange compare` does for each run and `lagrange sweep` for each shard and
/// for sbatch. (The launcher's processes, supervised and restarted, have
/// their own machinery in supervisor.hpp.)

#include <sys/types.h>

#include <string>
#include <vector>

namespace lagrange::wiring {

struct SpawnLog {
  std::string path;     ///< stdout and stderr of the child
  bool append = false;  ///< append to it (a restarted shard's log) instead of truncating
};

/// Starts argv (argv[0] a path, or a name looked up on PATH) without a shell.
/// `own_group`: the child leads a process group of its own, out of reach of
/// the terminal's Ctrl-C. @throws RuntimeFault naming argv[0] and why.
pid_t spawnLogged(const std::vector<std::string>& argv, const SpawnLog& log, bool own_group = false);

}  // namespace lagrange::wiring
