#pragma once
/// @file
/// Submitting a Slurm job array with sbatch: what `lagrange sweep --slurm`
/// (its shards) and `lagrange tune --slurm` (its starts) share -- the job
/// script, sbatch's command line with the user's options passed on, and the
/// job id read back (docs/sweeps.md, "On a Slurm cluster").

#include <sys/types.h>

#include <functional>
#include <string>
#include <vector>

namespace lagrange::wiring {

/// What the user asks of sbatch (--partition, --time, --account, --sbatch-arg).
struct SlurmOptions {
  std::string partition, time_limit, account;
  std::vector<std::string> sbatch_args;  ///< further sbatch options, passed as they are
  bool no_wait = false;                  ///< return once submitted (no sbatch --wait)
};

/// One job array: each task (its index in $SLURM_ARRAY_TASK_ID) runs `script`.
struct SlurmArray {
  std::string job_name;       ///< --job-name
  std::string indices;        ///< --array, e.g. "0-7" or "1,3"
  std::string script;         ///< the job script (written by writeJobScript)
  std::string output;         ///< --output, e.g. DIR/slurm/shard-%a.out
  std::string chdir;          ///< --chdir
  std::string sbatch_output;  ///< where sbatch's own output goes (the job id is read from it)
};

/// sbatch's command line for the array: --parsable, the array's settings,
/// the user's options, --wait unless no_wait, the script.
std::vector<std::string> sbatchCommand(const SlurmArray& array, const SlurmOptions& options);

/// Starts sbatch in a process group of its own (Ctrl-C stops the waiting,
/// not the job), its output to array.sbatch_output.
/// @throws RuntimeFault naming sbatch when it cannot be started.
pid_t submitSlurmArray(const SlurmArray& array, const SlurmOptions& options);

/// How the wait for sbatch ended (waitForSlurmArray).
struct SlurmWait {
  std::string job;       ///< the job id; "" when sbatch ended without submitting one
  int wstatus = 0;       ///< sbatch's wait status, once it ended
  bool stopped = false;  ///< stop() said stop first: sbatch (and the job) go on without us
};

/// Waits for the sbatch submitSlurmArray started (`pid`), looking every
/// 200 ms: `on_submitted(job)` once sbatch has printed the job id,
/// `on_poll()` at each look while it runs, and `stop()` (may be empty)
/// asked at each look. What a callback throws leaves the wait as it is.
SlurmWait waitForSlurmArray(pid_t pid, const SlurmArray& array,
                            const std::function<void(const std::string& job)>& on_submitted,
                            const std::function<void()>& on_poll, const std::function<bool()>& stop);

/// sbatch's output so far (array.sbatch_output; "" when there is none yet).
std::string sbatchOutputOf(const SlurmArray& array);

/// A child's wait status in words: "exited with code N", "was killed by signal N (NAME)".
std::string waitStatusText(int wstatus);

/// The job id sbatch --parsable prints ("ID" or "ID;CLUSTER") on a line of
/// its own, once it has submitted; warnings may come before it. Empty until then.
std::string slurmJobIdOf(const std::string& sbatch_output);

/// Whether Slurm's queue still lists job `job` (pending, running or
/// completing: `squeue -h -j JOB`). False for a job that has ended, an id
/// that is not a number, or no squeue.
bool slurmJobQueued(const std::string& job);

/// `s` quoted for a POSIX shell (single quotes).
std::string shellQuote(const std::string& s);

/// Writes a job script (never through a planted link), readable and
/// executable by all: the nodes run it as the user, from the shared folder.
void writeJobScript(const std::string& path, const std::string& text);

}  // namespace lagrange::wiring
