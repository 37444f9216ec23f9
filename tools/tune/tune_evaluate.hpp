#pragma once
/// @file
/// `lagrange tune`, one candidate: the scenario with the candidate's gains,
/// judged against the documented objective (docs/tuning.md), and the value
/// the search minimises. Runs simulations in process without a log; writes
/// nothing.

#include <Eigen/Dense>
#include <atomic>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/scenario.hpp"
#include "controller/registry.hpp"
#include "tools/tune/tune_search.hpp"
#include "util/error.hpp"
#include "wiring/sampled_simulation.hpp"

namespace lagrange::tools {

/// Thrown when a stop was requested midway through a candidate (nothing of it is kept).
struct TuneInterrupted : RuntimeFault {
  TuneInterrupted() : RuntimeFault("lagrange tune was interrupted") {}
};

/// The gains a candidate sets: each tunable gain's values, in the
/// declaration's order (one value for a gain that is not per joint).
using TuneGains = std::vector<std::pair<std::string, std::vector<double>>>;

/// What tune knows before the first candidate: the scenario as given, its
/// tunable gains, the search's variables, and what does not depend on the gains.
struct TuneProblem {
  std::string scenario_path;
  std::vector<std::string> overrides;  ///< the user's --set
  config::Scenario input;              ///< the scenario as given
  std::vector<controller::TunableGain> tunable;
  std::vector<SearchVariable> variables;  ///< one per joint of a per-joint gain, else one
  TuneGains input_gains;
  /// eq. (11)'s k_c and k_delta (printed (12); the paper's controllers only):
  /// of the robot and the reference, not the gains, so computed once.
  std::optional<double> kc, kdelta;
  double torque_limit = 0.0;  ///< [N m]: the largest saturation, else the input gains' peak (set later)
  bool torque_from_saturation = false;
  bool require_condition = false;
  int jobs = 0;  ///< the sampled-data check's processes (0: one per core)
  /// The local phase judges a candidate's run only up to cut_factor x the
  /// best feasible time so far (cutTime); 0: every run judged to its end
  /// (--full-runs; the objective before 2026-12-07).
  double cut_factor = 1.0;
};

/// The time up to which a candidate's run is judged, given the best
/// feasible convergence time so far: min(cut_factor x best, the deadline);
/// +inf with no best yet or cut_factor 0. A run whose error is at or above
/// the tolerance at a sample whose next sample time reaches it converges no
/// earlier than the cut, so it cannot beat the best: it is stopped there,
/// and valued by what it did up to the cut (docs/tuning.md, "The objective").
double cutTime(const TuneProblem& p, std::optional<double> best_time);
/// The first tick k whose next sample, (k + 1) x period, is at or past `cut`:
/// the last tick a cut run is judged on.
long long cutTick(double cut, double period);

/// The problem for a scenario. `span_decades`: each variable's range is the
/// declared one narrowed to span_decades decades either side of the input's
/// value. @throws config::ConfigError for a bad scenario; lagrange::BadInput
/// for a controller tune cannot search (external).
TuneProblem makeTuneProblem(const std::string& scenario_path, const std::vector<std::string>& overrides,
                            double span_decades);

/// A point of the search as gains.
TuneGains gainsOf(const TuneProblem& p, const std::vector<double>& point);
/// The --set strings that put `gains` into the scenario `input`
/// (controller.NAME=[...]; a stage's gains, "stages[i].KEY", as
/// controller.stages=[...] whole, the input's other keys of each stage kept).
std::vector<std::string> gainOverrides(const config::Scenario& input, const TuneGains& gains);
/// The input's controller.stages with the stage gains of `gains`, as flow
/// YAML; "" when `gains` has none.
std::string stagesYaml(const config::Scenario& input, const TuneGains& gains);

/// One candidate's findings (a line of tune.jsonl, docs/tuning.md).
struct TuneEvaluation {
  TuneGains gains;
  double value = 0.0;  ///< what the search minimises (tuneValue)
  /// true: every check passed; false: one failed (`failed` says which);
  /// none: not checked to the end, its run no faster than the best so far.
  std::optional<bool> feasible;
  std::string failed;                      ///< the first check that failed, in words
  std::string status;                      ///< the initial state's run: completed, diverged, cut (no run: "")
  std::optional<double> convergence_time;  ///< from the initial state [s]
  /// Judged only up to this time (status "cut"): its convergence time is at
  /// or past it, so neither it nor what follows is known; final_error and
  /// peak_torque are those of the part judged [s].
  std::optional<double> judged_to;
  /// With judged_to: the largest ||q~|| over the last quarter of the part
  /// judged -- how far from converged it still was [rad] -- and, when that
  /// is less than over the quarter before, the time at which the decay from
  /// one to the other would reach the tolerance (an estimate, above the
  /// cut) [s]; none when not decaying or too few ticks were judged.
  double late_error = 0.0;
  std::optional<double> estimated_time;
  double final_error = 0.0;             ///< [rad]
  double peak_torque = 0.0;             ///< max |tau_i| applied, from the initial state [N m]
  std::optional<double> margin;         ///< eq. (11)'s lhs - rhs (printed (12))
  std::optional<double> condition_lhs;  ///< (kd_min / 2)(b_min / a_max)
  std::string sampled_verdict;          ///< the simulated check's word; "": not run
  std::string sampled_why;
  std::vector<std::optional<double>> start_times;  ///< each start's sampled-loop convergence time [s]
  std::string linearised_verdict;                  ///< "": not run
  std::optional<double> sufficient_rate;           ///< the linearised check's, when not adequate [Hz]
  double wall_time = 0.0;                          ///< [s]
  /// Where wall_time went [s]: building the scenario, the run from the
  /// initial state, the sampled-data check (its simulations), the linearised check.
  double load_time = 0.0, run_time = 0.0, check_time = 0.0, linearised_time = 0.0;
};

/// The value of the findings (pure; docs/tuning.md, "The objective"):
/// a feasible candidate's (or one not checked to the end) is its
/// convergence time [s]; one judged only to its cut time X, its
/// estimated_time (above X: after the best's time and every time known
/// below it), or when none X + 1e4 + late_error / tolerance squeezed into
/// [0, 1) (below every band for X < 8e4 s); an infeasible one's a penalty above every
/// feasible value, by band, worst first -- the scenario refused 5e6, eq.
/// (11) violated with --require-condition [4e6, 5e6), the run diverged
/// [3e6, 4e6), the metric not met from the initial state [2e6, 3e6), the
/// torque over the limit [1e6, 2e6), the sampled-data check not ADEQUATE
/// or a start missing the metric [1e5, 2e5) -- ordered within a band by
/// how far it misses.
double tuneValue(const TuneEvaluation& e, const config::Scenario& s, double torque_limit);

/// A candidate is given the sampled-data check only when its run beats the
/// best so far by this share of the best's time (or two control periods,
/// whichever is more): a check costs 20 to 40 runs, and a local descent
/// improves by small steps. Those left unchecked are confirmed at the end
/// (tune's "confirm" phase), the fastest first.
inline constexpr double kCheckedGain = 0.01;

/// A candidate's first part, which depends on its gains alone: the
/// scenario with them (or its refusal), eq. (12), and the run from the
/// initial state. Tune makes it ahead of the search's asking, on several
/// threads (tools/tune/tune_ahead.hpp); judgeCandidate does the rest.
struct CandidateRun {
  TuneEvaluation findings;    ///< gains, margin, status, times, the run's numbers; `failed` when refused
  config::Scenario scenario;  ///< with the gains (the input's when refused)
  bool interrupted = false;   ///< the stop came during the run: nothing of it counts
  /// Per tick up to the deadline, for judging the run up to any cut time:
  /// ||q~||, and the largest |tau| so far.
  std::vector<double> errors, peaks;
  /// The run, when it went to its end: the sampled-data check's loop from
  /// the initial state, which the check then does not simulate again.
  std::optional<wiring::LoopOutcome> loop;
};

/// The first part. Never throws for a candidate's own failure (a refused
/// scenario, a diverged run: said in `findings`). `stop_requested` is asked
/// during the run. `cut_time` (null: none) is read at every tick: the run
/// stops at the first tick cutTime's rule says it can no longer beat the
/// best. It may only decrease while the run goes on, and judgeCandidate's
/// cut must be at or before it: what it judges is then the same whenever
/// the run stopped (runs made ahead on other threads stop at an older, later cut).
CandidateRun runCandidate(const TuneProblem& p, const TuneGains& gains, bool (*stop_requested)(),
                          const std::atomic<double>* cut_time = nullptr);

/// The rest: what the run says against the metric and the torque limit
/// (p.torque_limit; 0: none, for the input's own evaluation when the limit
/// is its peak), then the sampled-data check -- only when the run beats
/// `best_time`, the best feasible convergence time so far, by kCheckedGain
/// (else its value is its time and feasible unset). A run that does not
/// converge before `cut` (cutTime(p, best_time) in the local phase, else
/// +inf) is judged up to it alone (status "cut"): diverged before it, its
/// torque over the limit before it, or else not better (judged_to).
/// @throws TuneInterrupted
/// when the run was interrupted or `stop_requested` says stop after the check.
TuneEvaluation judgeCandidate(const TuneProblem& p, CandidateRun run, std::optional<double> best_time,
                              double cut, bool (*stop_requested)());

/// Both parts of `gains` at once.
TuneEvaluation evaluateGains(const TuneProblem& p, const TuneGains& gains, std::optional<double> best_time,
                             bool (*stop_requested)());

/// The linearised check (and its sufficient rate) of `gains`, for a message.
controller::SampledDataCheck linearisedCheckOf(const TuneProblem& p, const TuneGains& gains);

}  // namespace lagrange::tools
