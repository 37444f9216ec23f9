/// @file
/// `lagrange tune`: its command line (tools/tune/tune.hpp).
#include <CLI/CLI.hpp>
#include <memory>

#include "tools/tune/tune.hpp"

namespace lagrange::tools {

Subcommand addTuneCommand(CLI::App& app) {
  auto o = std::make_shared<TuneOptions>();
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
  cmd->add_option("scenario", o->scenario, "Scenario YAML file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", o->overrides, "Override a config key: key=value; repeatable");
  cmd->add_option("-o,--out", o->out_dir,
                  "Output directory (created if missing; resumed if it holds this tune)")
      ->required();
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
  cmd->add_flag("-q,--quiet", o->quiet, "Print errors only");
  return {cmd, [o](const Invocation&) { return runTune(*o); }};
}

}  // namespace lagrange::tools
