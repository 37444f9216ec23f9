#pragma once
/// @file
/// `lagrange tune`, its files in DIR (docs/tuning.md): tune.json (the
/// arguments a resume must match, and the result), tune.jsonl (every
/// evaluation, appended as it is made), tuned.yaml (the best gains as a
/// scenario extending the input), front.csv and front.png (the trade-off).

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/tune/tune_evaluate.hpp"

namespace lagrange::tools {

/// One line of tune.jsonl.
nlohmann::ordered_json evaluationJson(int index, SearchPhase phase, const TuneEvaluation& e,
                                      double torque_limit);
/// The evaluation a line holds (what a resume replays). @throws BadInput for a line that is not one.
TuneEvaluation evaluationFromJson(const nlohmann::ordered_json& line);

/// The evaluations already in DIR/tune.jsonl, by their point (the gains,
/// flattened in the variables' order): the search's (`phase` kStart: every
/// phase but confirm), or the confirm phase's (kConfirm). A torn last line
/// (an interrupt while writing) is dropped. @throws BadInput for a file
/// that is no tune's.
std::map<std::vector<double>, TuneEvaluation> readEvaluations(const std::string& dir, SearchPhase which);

/// The gains as one point, in the variables' order.
std::vector<double> flattened(const TuneGains& gains);

/// The evaluations of DIR/tune.jsonl in order, as written.
std::vector<nlohmann::ordered_json> readEvaluationLines(const std::string& dir);

/// Appends one line to DIR/tune.jsonl (flushed: an interrupt keeps it).
void appendEvaluation(const std::string& dir, const nlohmann::ordered_json& line);

/// The arguments that decide the search's sequence (a resume must repeat them).
nlohmann::ordered_json tuneArguments(const TuneProblem& p, unsigned seed, double span_decades, int global);

/// "DIR holds a KIND of an older lagrange, whose objective judged every run
/// to its end (...)": the start of the refusal of a folder from before the
/// cut (no `cut` in its arguments), a tune's or a Slurm tune's.
std::string olderObjectiveText(const std::string& dir, const std::string& kind);

/// tune.json's result.budget: `evaluations` (null: unbounded, --minutes
/// alone) and `minutes` (null: none) as a tune with these options runs them
/// (no --evaluations and no --minutes: the default, 200 evaluations).
nlohmann::ordered_json tuneBudget(int evaluations, double minutes);

/// Starts or resumes DIR: creates it, and compares tune.json's arguments
/// with `arguments` when tune.jsonl holds evaluations.
/// @throws BadInput naming the first argument that differs.
void prepareTuneDir(const std::string& dir, const nlohmann::ordered_json& arguments);

/// Writes DIR/tune.json: the arguments, and the result.
void writeTuneJson(const std::string& dir, const nlohmann::ordered_json& arguments,
                   const nlohmann::ordered_json& result);

/// Writes DIR/tuned.yaml: `extends:` the input (its path relative to DIR),
/// the user's --set as keys, and the controller section with `gains`.
void writeTunedYaml(const std::string& dir, const TuneProblem& p, const TuneGains& gains);

/// Writes DIR/front.csv and draws DIR/front.png with gnuplot: convergence
/// time against peak torque of every candidate that met the metric from the
/// initial state, coloured by eq. (12)'s margin, the input marked. Returns
/// why it was not drawn, or "".
std::string drawFront(const std::string& dir, const std::vector<nlohmann::ordered_json>& lines);

}  // namespace lagrange::tools
