#pragma once
/// @file
/// A run's verdict, decided in one place: whether the scenario's stated
/// metric was met, and why not -- the reasons in order of likelihood -- with
/// the warnings that matter whatever the result. Every reader of a run takes
/// it from summary.json's `verdict` (the terminal's final block, `--check`,
/// compare's table, sweep's rows, the Python reader, the viewer); none
/// decides it again. docs/summary.md ("The verdict") lists every reason and
/// warning, with the thresholds below.
///
/// Pure: a function of the summary's other fields, so that the launcher can
/// decide it again after adding what only it knows (a process's failure).

#include <nlohmann/json.hpp>
#include <string>

namespace lagrange::logger {

/// Thresholds of the timing reason and warning (documented in docs/summary.md).
struct VerdictThresholds {
  /// A realtime loop on time less often than this is a timing fault.
  double on_time_fraction = 0.99;
  /// ... and so is a run of this many consecutive missed deadlines.
  long long longest_miss_run = 10;
  /// The plant's torque held or zeroed (no fresh one) on more than this
  /// share of its periods is a timing fault; on any period, a warning.
  double stale_torque_fraction = 0.001;
  /// The error grew when its largest exceeds this many times the larger of
  /// its start and the tolerance, and the run ended farther than it began.
  double growth = 5.0;
  /// The plant's samples (PLANT_TRUTH) missing from the log on more than
  /// this share of the run's ticks leave the figures without the run: in
  /// realtime (a datagram lost on the way is no fault of the controller);
  /// in lockstep, where the plant re-sends until the logger has each, any.
  double missing_truth_fraction = 0.01;
};

/// summary.json's `verdict` from the rest of the summary (docs/summary.md):
///   {tracking: "met" | "NOT met" | "not judged",
///    met: bool, headline: the sentence the terminal's first line carries,
///    reasons: [{kind, text}] (why not met, most likely first; empty when met),
///    warnings: [{kind, text}]}
/// Missing fields are read as absent (an older summary still gets a verdict).
nlohmann::json runVerdict(const nlohmann::json& summary, const VerdictThresholds& limits = {});

/// The one sentence a table row shows of a verdict: its likeliest reason
/// when missed; for a met run its first warning, as "warning: ..."; empty
/// when there is neither (or `verdict` is not one).
std::string likeliestReason(const nlohmann::json& verdict);

}  // namespace lagrange::logger
