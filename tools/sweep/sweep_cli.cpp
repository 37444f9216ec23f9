/// @file
/// `lagrange sweep`, `lagrange sweep collect` and the internal `sweep-shard`:
/// their command lines (tools/sweep/sweep.hpp).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "tools/slurm_options.hpp"
#include "tools/sweep/sweep.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

namespace {
struct SweepCommandLine {
  SweepOptions sweep;
  CLI::App* collect = nullptr;
  std::string collect_dir;
  bool collect_quiet = false;
};

struct ShardCommandLine {
  std::string out_dir;
  int shard = -1, of = 0, parent = 0;
  std::string plan_digest;
};
}  // namespace

Subcommand addSweepCommand(CLI::App& app) {
  auto o = std::make_shared<SweepCommandLine>();
  SweepOptions& options = o->sweep;
  CLI::App* cmd = app.add_subcommand("sweep", "Run a scenario many times over axes of its keys");
  describeCommand(
      *cmd,
      "Run a scenario many times in-process over axes of its keys (lists, linear and log ranges, initial "
      "errors by norm and random direction; grids, seeded random or Halton samples), on every core or as a "
      "Slurm job array; write one row per run (parameters, convergence time, final and max error, diverged, "
      "the gain verdicts, wall time) to OUT/sweep.csv and OUT/sweep.jsonl, and maps as PNGs. Resumable: run "
      "the same command again after a stop (docs/sweeps.md)",
      {"lagrange sweep sweeps/first_sweep.yaml --out runs/first_sweep",
       "lagrange sweep sweeps/rigid_rates.yaml --out runs/rates --dry-run"});
  cmd->add_option("sweep_file", options.sweep_file, "Sweep YAML file, e.g. sweeps/rigid_rates.yaml")
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", options.out_dir,
                  "Output directory (created if missing; resumed if it holds this sweep)");
  cmd->add_option("-j,--jobs", options.jobs, "Local runs at a time (default: one per core)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("-q,--quiet", options.quiet, "Print errors only");
  cmd->add_flag("--dry-run", options.dry_run,
                "Plan the sweep and check every run's scenario, print how many runs it has; run nothing");
  cmd->add_flag("--slurm", options.slurm,
                "Submit the runs as a Slurm job array (sbatch) instead of running them here; OUT must be on "
                "a directory every node shares, and this binary on every node at the same path");
  addSlurmOptions(*cmd, options.slurm_options, "lagrange sweep collect OUT", "--qos=long");
  cmd->add_option("--shards", options.shards, "--slurm: array tasks (default: min(runs to do, 64))")
      ->check(CLI::PositiveNumber);
  o->collect = cmd->add_subcommand("collect", "Merge a sweep's rows into its table and maps");
  describeCommand(
      *o->collect,
      "Merge the rows a sweep's shards wrote (a Slurm sweep run with --no-wait, or a stopped one) "
      "into OUT/sweep.csv, OUT/sweep.jsonl and the maps; exit 1 if rows are missing (docs/sweeps.md)",
      {"lagrange sweep collect runs/first_sweep"});
  o->collect->add_option("out", o->collect_dir, "The sweep's output directory")
      ->required()
      ->check(CLI::ExistingDirectory);
  o->collect->add_flag("-q,--quiet", o->collect_quiet, "Print errors only");
  return {cmd, [o](const Invocation& inv) {
            if (*o->collect) return collectSweep(o->collect_dir, o->collect_quiet);
            SweepOptions sweep = o->sweep;
            if (sweep.sweep_file.empty() || (sweep.out_dir.empty() && !sweep.dry_run)) {
              std::cerr
                  << "lagrange sweep: expected a sweep file and --out DIR (or: lagrange sweep collect DIR)\n";
              return static_cast<int>(kExitBadInput);
            }
            sweep.self_exe = inv.self_exe;
            return runSweep(sweep);
          }};
}

Subcommand addSweepShardCommand(CLI::App& app) {
  auto o = std::make_shared<ShardCommandLine>();
  CLI::App* cmd = app.add_subcommand("sweep-shard", "One shard of a sweep (what lagrange sweep starts)");
  cmd->group("");  // internal: not listed in --help
  cmd->add_option("out", o->out_dir, "The sweep's output directory")->required();
  cmd->add_option("--shard", o->shard, "This shard, K in 0..N-1")->required();
  cmd->add_option("--of", o->of, "Shards, N")->required();
  cmd->add_option("--parent", o->parent, "The local sweep's pid: stop when it ends");
  cmd->add_option("--plan-digest", o->plan_digest,
                  "SHA-256 of the plan the sweep launched: any other plan.json is refused")
      ->required();
  return {cmd, [o](const Invocation& inv) {
            return runSweepShard(o->out_dir, o->shard, o->of, o->plan_digest, o->parent, inv.self_exe);
          }};
}

}  // namespace lagrange::tools
