#pragma once
/// @file
/// The sbatch options `lagrange sweep --slurm` and `lagrange tune --slurm`
/// both take, declared once on a command (docs/sweeps.md, "On a Slurm cluster").

#include <CLI/CLI.hpp>
#include <string>

#include "wiring/slurm_array.hpp"

namespace lagrange::tools {

/// --no-wait, --partition, --time, --account and --sbatch-arg into `o`.
/// `collect`: the command that collects after --no-wait (e.g. "lagrange
/// sweep collect OUT"); `sbatch_arg_example`: an sbatch option for the help.
inline void addSlurmOptions(CLI::App& cmd, wiring::SlurmOptions& o, const std::string& collect,
                            const std::string& sbatch_arg_example) {
  cmd.add_flag("--no-wait", o.no_wait, "--slurm: return once the job is submitted; then `" + collect + "`");
  cmd.add_option("--partition", o.partition, "--slurm: sbatch --partition");
  cmd.add_option("--time", o.time_limit, "--slurm: sbatch --time, each array task's limit");
  cmd.add_option("--account", o.account, "--slurm: sbatch --account");
  cmd.add_option(
      "--sbatch-arg", o.sbatch_args,
      "--slurm: one more sbatch option as it is, e.g. --sbatch-arg=" + sbatch_arg_example + "; repeatable");
}

}  // namespace lagrange::tools
