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
};

struct SearchOutcome {
  std::vector<double> best;  ///< the point of the smallest value seen
  double best_value = 0.0;
  int evaluations = 0;  ///< calls made
};

/// Runs the search. @throws std::invalid_argument for variables without a
/// valid range, or no variables; whatever the objective throws.
SearchOutcome search(const std::vector<SearchVariable>& variables, const SearchSettings& settings,
                     const SearchObjective& objective);

}  // namespace lagrange::tools
