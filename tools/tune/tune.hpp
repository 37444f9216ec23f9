#pragma once
/// @file
/// `lagrange tune SCENARIO --out DIR`: searches the scenario's controller
/// gains for the earliest convergence time that passes the checks
/// (docs/tuning.md): the metric from the initial state and the sampled-data
/// check's seeded states, the simulated sampled-data check ADEQUATE at the
/// scenario's rate, |torque| within the saturation (or the input gains'
/// peak); eq. (12)'s margin reported, and required with --require-condition.

#include <string>
#include <vector>

#include "tools/subcommand.hpp"
#include "wiring/slurm_array.hpp"

namespace lagrange::tools {

struct TuneOptions {
  std::string scenario;
  std::vector<std::string> overrides;  ///< --set KEY=VALUE
  std::string out_dir;
  int evaluations = 0;   ///< the budget in evaluations; 0: kDefaultEvaluations unless minutes is set
  double minutes = 0.0;  ///< the budget in wall time; 0: none
  int jobs = 0;          ///< candidates run at a time, and the check's simulations; 0: one per core
  unsigned seed = 1;
  double span = 2.0;  ///< decades either side of the input's gains
  int global = 0;     ///< the global phase's evaluations; 0: 10 (n + 1)
  bool require_condition = false;
  bool full_runs = false;  ///< no cut: every candidate's run judged to its end (docs/tuning.md)
  bool quiet = false;
  // --slurm (docs/tuning.md, "On a Slurm cluster"): independent searches,
  // one seed each, as one job array; the best of them is the result.
  bool slurm = false;
  int starts = 0;  ///< --slurm: array tasks, seeds seed .. seed + starts - 1; 0: kDefaultStarts
  wiring::SlurmOptions slurm_options;
  std::string self_exe;  ///< this lagrange binary (every node runs it)
};

inline constexpr int kDefaultEvaluations = 200;
inline constexpr int kDefaultStarts = 8;

/// Runs the tune. Exit 0 when gains that pass every check were found, 1
/// when none was (what binds is named), 2 for bad input, 130 interrupted.
int runTune(const TuneOptions& options);

struct TuneProblem;
/// The problem `options` asks for, checked as a tune starts (--span, the
/// scenario, --require-condition). @throws BadInput, config::ConfigError.
TuneProblem checkedTuneProblem(const TuneOptions& options);

/// Declares `tune` (and `tune collect`) on the front end.
Subcommand addTuneCommand(CLI::App& app);

}  // namespace lagrange::tools
