/// @file
/// `lagrange tune`: its command line (tools/tune/tune.hpp).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "tools/slurm_options.hpp"
#include "tools/tune/tune.hpp"
#include "tools/tune/tune_slurm.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

Subcommand addTuneCommand(CLI::App& app) {
  struct TuneCommandLine {
    TuneOptions tune;
    CLI::App* collect = nullptr;
    std::string collect_dir;
    bool collect_quiet = false;
  };
  auto line = std::make_shared<TuneCommandLine>();
  TuneOptions* o = &line->tune;
  CLI::App* cmd = app.add_subcommand("tune", "Search gains: the fastest that pass the checks");
  describeCommand(
      *cmd,
      "Search the scenario's controller gains (each controller declares its tunable gains and their ranges) "
      "for the earliest convergence time that passes the checks: the metric met from the initial state and "
      "from the sampled-data check's seeded states, the simulated sampled-data check ADEQUATE at the "
      "scenario's rate, |torque| within actuator.saturation (else within the input gains' peak). NLopt: a "
      "seeded global phase (CRS2) then a local one (subplex), on log-scaled gains. Writes OUT/tune.jsonl "
      "(every evaluation; a rerun with the same arguments resumes from it), OUT/tuned.yaml (a scenario that "
      "extends the input with the best gains), OUT/tune.json and OUT/front.png. A local search over a few "
      "initial states, not a proof. Exit 0 gains found, 1 none passed (what binds is named), 2 bad input, "
      "130 interrupted (docs/tuning.md)",
      {"lagrange tune configs/rigid_2dof.yaml --out runs/tuned --evaluations 8 --set duration=3"});
  cmd->add_option("scenario", o->scenario, "Scenario YAML file (required but with `collect`)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", o->overrides, "Override a config key: key=value; repeatable");
  cmd->add_option("-o,--out", o->out_dir,
                  "Output directory (created if missing; resumed if it holds this tune)");
  cmd->add_option("--evaluations", o->evaluations,
                  "Evaluations in all, the input's included (default 200, or unbounded with --minutes)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--minutes", o->minutes, "Stop starting evaluations after this much wall time")
      ->check(CLI::PositiveNumber);
  cmd->add_option("-j,--jobs", o->jobs,
                  "Candidates run at a time, ahead of the search, and the sampled-data check's "
                  "simulations at a time (default: one per core)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--seed", o->seed, "The global phase's random seed: the same seed, the same evaluations");
  cmd->add_option("--span", o->span,
                  "Decades searched either side of the input's gains, within each gain's declared range "
                  "(default 2)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--global", o->global,
                  "The global phase's evaluations (default 10 (n + 1), n gains searched)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag(
      "--require-condition", o->require_condition,
      "Keep only gains for which eq. (12) holds (the paper's guarantee); if none, name the reference "
      "size for which it could");
  cmd->add_flag("--full-runs", o->full_runs,
                "Judge every candidate's run to its end, none cut once it cannot beat the best: slower, "
                "and every candidate's convergence time known (front.png draws each that met the metric)");
  cmd->add_flag("-q,--quiet", o->quiet, "Print errors only");
  cmd->add_flag(
      "--slurm", o->slurm,
      "Run --starts independent searches (seeds --seed, --seed + 1, ...) as a Slurm job array, each "
      "into OUT/starts/K, and keep the best; OUT on a directory every node shares, this binary on "
      "every node at the same path (docs/tuning.md)");
  cmd->add_option("--starts", o->starts, "--slurm: searches, one array task each, 1 to 100000 (default 8)")
      ->check(CLI::Range(1, 100000).description(""));
  addSlurmOptions(*cmd, o->slurm_options, "lagrange tune collect OUT", "--cpus-per-task=4");
  line->collect = cmd->add_subcommand("collect", "The best of a Slurm tune's starts");
  describeCommand(
      *line->collect,
      "Collect the starts of a tune run with --slurm (after --no-wait, or a stopped wait): the best "
      "of them into OUT/tuned.yaml, OUT/tune.json and OUT/front.png; exit 1 while a start is not "
      "finished or when none passed (docs/tuning.md)",
      {"lagrange tune collect runs/tuned"});
  line->collect->add_option("out", line->collect_dir, "The tune's output directory")
      ->required()
      ->check(CLI::ExistingDirectory);
  line->collect->add_flag("-q,--quiet", line->collect_quiet, "Print errors only");
  return {
      cmd, [line](const Invocation& inv) {
        TuneOptions options = line->tune;
        if (*line->collect) {
          if (!options.scenario.empty() || !options.out_dir.empty() || !options.overrides.empty() ||
              options.slurm || options.starts != 0) {
            std::cerr << "lagrange tune collect: a scenario, --out, --set, --slurm or --starts given with "
                         "collect; expected only `lagrange tune collect DIR` (and -q)\n";
            return static_cast<int>(kExitBadInput);
          }
          return collectTune(line->collect_dir, line->collect_quiet || options.quiet);
        }
        if (options.scenario.empty() || options.out_dir.empty()) {
          std::cerr << "lagrange tune: expected a scenario and --out DIR (or: lagrange tune collect DIR)\n";
          return static_cast<int>(kExitBadInput);
        }
        options.self_exe = inv.self_exe;
        return runTune(options);
      }};
}

}  // namespace lagrange::tools
