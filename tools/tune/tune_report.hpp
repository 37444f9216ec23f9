#pragma once
/// @file
/// `lagrange tune`, what it prints and keeps of a result (docs/tuning.md):
/// the gains and times in words, what binds when nothing passed, the summary
/// of the best against the input -- for one tune and for the best of a
/// Slurm tune's starts alike.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tools/tune/tune_evaluate.hpp"

namespace lagrange::tools {

/// `v` in printf's `format` (by default 4 significant digits).
std::string shortNumber(double v, const char* format = "%.4g");
/// "1.234 s", or "none".
std::string seconds(const std::optional<double>& t);
/// "kp [150, 10], kd 5".
std::string gainsText(const TuneGains& gains);

/// What keeps every candidate out, in words (docs/tuning.md, "When nothing
/// passes"): the reference's size for eq. (12) with --require-condition,
/// the rate, the torque limit, the metric itself.
std::vector<std::string> whatBinds(const TuneProblem& p, const std::vector<TuneEvaluation>& all);

/// One side (input or best) of tune.json's result.
nlohmann::ordered_json side(const TuneEvaluation& e);

/// The terminal's table: the best against the input's gains.
void printSummary(const TuneEvaluation& input, const TuneEvaluation& best, const TuneProblem& p);

}  // namespace lagrange::tools
