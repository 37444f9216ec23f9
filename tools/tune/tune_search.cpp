#include "tools/tune/tune_search.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <nlopt.hpp>
#include <stdexcept>
#include <string>
#include <utility>

namespace lagrange::tools {

const char* toString(SearchPhase phase) {
  switch (phase) {
    case SearchPhase::kStart:
      return "start";
    case SearchPhase::kGlobal:
      return "global";
    case SearchPhase::kLocal:
      return "local";
    case SearchPhase::kConfirm:
      return "confirm";
  }
  return "?";
}

int defaultGlobalEvaluations(size_t n) { return std::min(10 * static_cast<int>(n + 1), kMostGlobal); }

namespace {

// What the NLopt callback needs: the objective, the phase, the budget left,
// the best so far, and an exception of the objective's, kept to rethrow
// (NLopt's C++ wrapper turns any exception into a bare failure).
struct Run {
  const SearchObjective* objective = nullptr;
  SearchPhase phase = SearchPhase::kStart;
  int left = 0;
  SearchOutcome* outcome = nullptr;
  std::exception_ptr error;
  nlopt::opt* opt = nullptr;
  // The start in both scales: where NLopt hands back log(start), the
  // objective gets the start itself, not exp(log(start)) a rounding off
  // (the input's gains are then the same point, and read from a cache).
  std::vector<double> log_start, start;
  // A replay (search with a lookahead): the calls made so far, in order,
  // with their values, given back instead of the objective's; the points
  // after them met so far (the first is the next call), and its phase.
  const std::vector<std::pair<std::vector<double>, double>>* known = nullptr;
  size_t replayed = 0;
  size_t lookahead = 1;
  std::vector<std::vector<double>> ahead;
  SearchPhase ahead_phase = SearchPhase::kStart;
  bool ahead_full = false;  // the replay has found all it looks for: every phase ends
};

// A replay's value for a point it does not know: worse than any.
constexpr double kGuessed = 1e300;

// A replay's value of the call of `point`: the known one (calls are matched
// by their place in the sequence, as a search without a lookahead repeats a
// point's call), else the guess (the point noted).
double replayed(Run& run, const std::vector<double>& point) {
  if (run.replayed < run.known->size()) {
    const auto& [was, value] = (*run.known)[run.replayed++];
    if (was != point)  // NLopt gave another point for the same values: not deterministic
      throw std::logic_error("the search's replay asked another point at call " +
                             std::to_string(run.replayed));
    return value;
  }
  if (run.ahead.empty()) run.ahead_phase = run.phase;
  if (std::find(run.ahead.begin(), run.ahead.end(), point) == run.ahead.end()) run.ahead.push_back(point);
  if (run.ahead.size() >= run.lookahead) {
    run.ahead_full = true;
    if (run.opt) run.opt->force_stop();
  }
  return kGuessed;
}

double call(Run& run, const std::vector<double>& log_point) {
  // Stopped: NLopt may call again before it looks (CRS2 draws its whole
  // population first); the objective is not asked again.
  if (run.error || run.ahead_full) return std::numeric_limits<double>::infinity();
  // The budget is the caller's: NLopt's own count may run one over (CRS2's
  // mutation step evaluates two points before it looks).
  if (run.left <= 0) {
    if (run.opt) run.opt->force_stop();
    return std::numeric_limits<double>::infinity();
  }
  std::vector<double> point(log_point.size());
  for (size_t i = 0; i < point.size(); ++i)
    point[i] = log_point[i] == run.log_start[i] ? run.start[i] : std::exp(log_point[i]);
  double value = std::numeric_limits<double>::infinity();
  if (run.known) {
    try {
      value = replayed(run, point);
    } catch (...) {
      run.error = std::current_exception();
      if (run.opt) run.opt->force_stop();
      return value;
    }
  } else {
    try {
      value = (*run.objective)(point, run.phase);
    } catch (...) {
      run.error = std::current_exception();
      if (run.opt) run.opt->force_stop();
      return value;
    }
  }
  --run.left;
  ++run.outcome->evaluations;
  if (run.outcome->best.empty() || value < run.outcome->best_value) {
    run.outcome->best = point;
    run.outcome->best_value = value;
  }
  return value;
}

double callback(unsigned n, const double* x, double* /*grad: derivative-free*/, void* data) {
  Run& run = *static_cast<Run*>(data);
  return call(run, std::vector<double>(x, x + n));
}

// One phase of at most run.left calls (nothing when none is left).
void phase(Run& run, nlopt::algorithm algorithm, SearchPhase which, int most,
           const std::vector<double>& lower, const std::vector<double>& upper, std::vector<double> start) {
  const int calls = std::min(most, run.left);
  if (calls <= 0 || run.error || run.ahead_full) return;
  nlopt::opt opt(algorithm, static_cast<unsigned>(lower.size()));
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_min_objective(callback, &run);
  opt.set_maxeval(calls);
  if (which == SearchPhase::kLocal) {
    opt.set_xtol_rel(1e-4);
    // Subplex's first steps: a factor of e^0.4 (about 1.5) per gain, or a
    // quarter of the box where that is narrower. NLopt's default, a quarter
    // of the box (a factor of 10 in +-2 decades), throws a many-joint arm's
    // loop unstable at every first step (docs/tuning.md).
    std::vector<double> step(lower.size());
    for (size_t i = 0; i < step.size(); ++i) step[i] = std::min(kLocalStep, 0.25 * (upper[i] - lower[i]));
    opt.set_initial_step(step);
  }
  // CRS2's population (NLopt's default, 10 (n + 1), would spend the whole
  // default global phase drawing it): half the phase, at least n + 1.
  if (which == SearchPhase::kGlobal)
    opt.set_population(
        static_cast<unsigned>(std::max<size_t>(lower.size() + 1, static_cast<size_t>(most / 2))));
  run.phase = which;
  run.opt = &opt;
  double value = 0.0;
  try {
    opt.optimize(start, value);
  } catch (const nlopt::forced_stop&) {
  } catch (const nlopt::roundoff_limited&) {  // converged as far as doubles tell: a normal end
  } catch (const std::runtime_error&) {
    // NLopt's own failure -- unless a replay had its next point already: a
    // failure past it may come of the guessed values, which the search never sees.
    if (!run.error && !(run.known && !run.ahead.empty())) throw;
    if (run.known && !run.ahead.empty()) run.ahead_full = true;
  }
  run.opt = nullptr;
  if (run.error) std::rethrow_exception(run.error);
}

}  // namespace

namespace {

// The search's box on the log scale, and the start in both scales.
struct Box {
  std::vector<double> lower, upper, start, real_start;
};

Box boxOf(const std::vector<SearchVariable>& variables) {
  if (variables.empty()) throw std::invalid_argument("nothing to search: no variables");
  const size_t n = variables.size();
  Box b{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)};
  for (size_t i = 0; i < n; ++i) {
    const SearchVariable& v = variables[i];
    if (!(v.lower > 0.0) || !(v.upper > v.lower))
      throw std::invalid_argument("the search variable " + v.label +
                                  " has no valid range; expected 0 < lower < upper");
    b.lower[i] = std::log(v.lower);
    b.upper[i] = std::log(v.upper);
    b.real_start[i] = std::clamp(v.start > 0.0 ? v.start : std::sqrt(v.lower * v.upper), v.lower, v.upper);
    b.start[i] = std::log(b.real_start[i]);
  }
  return b;
}

// The whole sequence once: the start, the global phase, the local one.
SearchOutcome pass(const Box& box, const SearchSettings& settings, Run& run) {
  const size_t n = box.lower.size();
  SearchOutcome outcome;
  run.left = settings.max_evaluations;
  run.outcome = &outcome;
  run.log_start = box.start;
  run.start = box.real_start;
  if (run.left <= 0) return outcome;

  // The start first: the input's gains are what every candidate is compared with.
  run.phase = SearchPhase::kStart;
  call(run, box.start);
  if (run.error) std::rethrow_exception(run.error);

  const int global =
      settings.global_evaluations > 0 ? settings.global_evaluations : defaultGlobalEvaluations(n);
  nlopt::srand(settings.seed);  // CRS2's draws: the same points for the same seed
  phase(run, nlopt::GN_CRS2_LM, SearchPhase::kGlobal, global, box.lower, box.upper, box.start);
  if (run.ahead_full) return outcome;

  std::vector<double> best_log(n);
  std::transform(outcome.best.begin(), outcome.best.end(), best_log.begin(),
                 [](double x) { return std::log(x); });
  for (size_t i = 0; i < n; ++i) best_log[i] = std::clamp(best_log[i], box.lower[i], box.upper[i]);
  phase(run, nlopt::LN_SBPLX, SearchPhase::kLocal, run.left, box.lower, box.upper, best_log);
  return outcome;
}

}  // namespace

SearchOutcome search(const std::vector<SearchVariable>& variables, const SearchSettings& settings,
                     const SearchObjective& objective, const SearchLookahead& lookahead) {
  const Box box = boxOf(variables);
  if (!lookahead || settings.lookahead <= 1) {
    Run run;
    run.objective = &objective;
    return pass(box, settings, run);
  }
  // Replays: each finds the next call (and the guessed ones after it), the
  // objective gives its value, and the next replay knows it.
  std::vector<std::pair<std::vector<double>, double>> known;
  for (;;) {
    Run run;
    run.known = &known;
    run.lookahead = static_cast<size_t>(settings.lookahead);
    SearchOutcome outcome = pass(box, settings, run);
    if (run.ahead.empty()) return outcome;  // every call's value known: the search has ended
    lookahead(run.ahead);
    const double value = objective(run.ahead.front(), run.ahead_phase);
    known.emplace_back(run.ahead.front(), value);
  }
}

}  // namespace lagrange::tools
