#pragma once
/// @file
/// `lagrange tune`, its search: NLopt's derivative-free bounded optimisers
/// over positive gains on a log scale, with no I/O and no clock. The
/// objective (what a candidate's value is, when to stop) is the caller's.
///
/// The sequence: the start point first; then a global phase (NLopt's
/// GN_CRS2_LM, controlled random search with local mutation, seeded by
/// `seed` through nlopt::srand) of at most `global_evaluations` calls
/// (defaultGlobalEvaluations); then
/// a local phase (LN_SBPLX, Rowan's subplex: a Nelder-Mead variant that
/// tolerates the penalty's steps) from the best point found, until the budget
/// is spent or it converges (relative step 1e-4). The global phase's length
/// does not depend on the total budget, so that a longer budget repeats a
/// shorter one's calls, point for point, before going on (resuming replays
/// them from a cache).

#include <functional>
#include <string>
#include <vector>

namespace lagrange::tools {

/// One searched number: a gain of one joint (or of every joint), positive.
struct SearchVariable {
  std::string label;   ///< e.g. "kp[0]"
  double lower = 0.0;  ///< 0 < lower < upper
  double upper = 0.0;
  double start = 0.0;  ///< clamped into [lower, upper]
};

/// kConfirm is not the search's: tune's last evaluations, the sampled-data
/// check of the fastest runs the search left unchecked (docs/tuning.md).
enum class SearchPhase { kStart, kGlobal, kLocal, kConfirm };
const char* toString(SearchPhase phase);

/// The value of the candidate `point` (one number per variable, in the
/// variables' own units); lower is better. It may throw to end the search
/// (the exception leaves search() as it is).
using SearchObjective = std::function<double(const std::vector<double>& point, SearchPhase phase)>;

/// The points the search will ask for next, handed over before the first of
/// them is asked: `points[0]` is the next call's; the others are the calls
/// that would follow were each value worse than any (a guess: they may never
/// be asked). For making evaluations ahead of the search, in parallel
/// (tune's runs, tools/tune/tune_ahead.hpp); the search's sequence is the
/// same with and without it.
using SearchLookahead = std::function<void(const std::vector<std::vector<double>>& points)>;

/// The global phase's default length: 10 (n + 1), at most kMostGlobal. In
/// many dimensions (the Panda's 28 gains) random points of the box are
/// almost all unstable loops; the budget is better spent descending from
/// the best of them (the input's gains, as a rule).
inline constexpr int kMostGlobal = 60;
int defaultGlobalEvaluations(size_t n);
/// The local phase's first step on the log scale (e^0.4: a factor of about 1.5).
inline constexpr double kLocalStep = 0.4;

struct SearchSettings {
  unsigned seed = 1;
  int max_evaluations = 100;   ///< calls of the objective in all, the start's included
  int global_evaluations = 0;  ///< the global phase's most; 0: defaultGlobalEvaluations(n)
  /// Points handed to the lookahead at once, the next one's included; 1: no lookahead.
  int lookahead = 1;
};

struct SearchOutcome {
  std::vector<double> best;  ///< the point of the smallest value seen
  double best_value = 0.0;
  int evaluations = 0;  ///< calls made
};

/// Runs the search. With a lookahead (and settings.lookahead > 1) the
/// optimisers are replayed from the start for each call, the values of the
/// calls made so far given back in order, up to the first call without one:
/// its point is the next call's, and the replay goes on past it with a
/// guessed value (worse than any) to find the points handed to the
/// lookahead with it. The calls
/// of the objective, their order and the outcome are those of the search
/// without a lookahead: NLopt is deterministic for the same values and seed
/// (CRS2's population, drawn before any value is looked at, is always
/// guessed right; a subplex step only when the value was bad).
/// @throws std::invalid_argument for variables without a valid range, or no
/// variables; whatever the objective throws.
SearchOutcome search(const std::vector<SearchVariable>& variables, const SearchSettings& settings,
                     const SearchObjective& objective, const SearchLookahead& lookahead = {});

}  // namespace lagrange::tools
