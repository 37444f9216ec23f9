#pragma once
/// @file
/// `lagrange sweep`: many in-process runs of one scenario over axes of its
/// keys (docs/sweeps.md). Locally, shards of the plan run as processes, one
/// per core; with --slurm they run as a Slurm job array. Either way the rows
/// land in OUT/rows/ and the table is made from them, so a killed or partial
/// sweep loses nothing finished and a restart runs only what is missing.

#include <string>
#include <vector>

#include "tools/subcommand.hpp"
#include "wiring/slurm_array.hpp"

namespace lagrange::tools {

struct SweepOptions {
  std::string sweep_file;
  std::string out_dir;
  int jobs = 0;  ///< local shards at a time; 0: one per core
  bool quiet = false;
  bool dry_run = false;  ///< plan and check every row, print the count, run nothing, write nothing
  bool slurm = false;    ///< submit the shards as a Slurm job array
  int shards = 0;        ///< --slurm: array tasks; 0: min(runs left, 64)
  wiring::SlurmOptions slurm_options;  ///< --slurm: sbatch's options, --no-wait
  std::string self_exe;                ///< this lagrange binary (every node runs it)
};

/// Plans (exit 2 naming what is wrong, before any run), runs what is not yet
/// in OUT/rows, then writes the table and maps. 0: every row is in the table;
/// 1: rows are missing (a shard failed, or --no-wait); 2: also when lines or
/// files in OUT/rows were refused (sweep_store.hpp: named on stderr, left
/// out of the table); 130: interrupted.
int runSweep(const SweepOptions& options);

/// `lagrange sweep collect OUT`: the table and maps from what the shards
/// wrote. 0 when every row is there, 1 when some are missing (the table then
/// has the others), 2 when OUT is not a sweep or something in OUT/rows was
/// refused (not this plan's rows: named on stderr; a table already there is
/// left as it was, byte for byte, with its maps; without one, the table has the rest).
int collectSweep(const std::string& out_dir, bool quiet);

/// One shard (`lagrange sweep-shard OUT --shard K --of N`, what the local
/// sweep and each Slurm array task run): the rows with index % N == K that
/// no file in OUT/rows has, in order, each appended to
/// OUT/rows/shard-K-of-N.jsonl as it ends. 0, or 130 when stopped by a signal.
/// `parent` > 0 (a local shard): the sweep's pid; the shard stops when it dies.
/// `self_exe`: the lagrange binary, which runs the rows of an external
/// controller (`lagrange run --mode lockstep`). `plan_digest`: SHA-256 (hex)
/// of the plan the sweep launched; a plan.json that is not that plan is
/// refused before anything of it runs (exit 2).
int runSweepShard(const std::string& out_dir, int shard, int of, const std::string& plan_digest,
                  int parent = 0, const std::string& self_exe = "");

/// Declares `sweep` (with `sweep collect`) and its options on the front end (tools/sweep/sweep_cli.cpp).
Subcommand addSweepCommand(CLI::App& app);

/// Declares the internal `sweep-shard` and its options on the front end (tools/sweep/sweep_cli.cpp).
Subcommand addSweepShardCommand(CLI::App& app);

}  // namespace lagrange::tools
