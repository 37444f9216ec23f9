#pragma once
/// @file
/// `lagrange run --check[=LIST]` and `--junit FILE`: what a CI job asks of a
/// run, checked against its summary.json.
///
/// A check is `met` -- the scenario's stated metric, ||q~|| below
/// metrics.tolerance by metrics.convergence_deadline and staying there (and
/// every chain stage's); a miss names the verdict's reasons --,
/// `no_warnings` -- the run's verdict (summary.json `verdict.warnings`)
/// lists none: no timing fault, stale torque, slow answer, missing tick --
/// or `KEY OP NUMBER`: KEY a number of summary.json
/// by its dotted path (`tracking.final_error`, `torque.max_abs`) or by the
/// last part where that is one of the common ones (final_error, max_error,
/// convergence_time, rms_last_second, max_torque), OP one of < <= > >=.
/// A run that did not complete fails every check. A convergence_time that
/// is null (never converged) fails every comparison.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lagrange::tools {

struct MetricCheck {
  std::string text;  ///< as the user wrote it, e.g. "final_error<1e-4"
  std::string key;   ///< summary.json's dotted path; "met" for the stated metric
  std::string op;    ///< "<", "<=", ">", ">="; empty for "met"
  double threshold = 0.0;
};

/// Reads one check. @throws config::ConfigError naming the text and the
/// grammar (exit 2 before the run starts).
MetricCheck parseMetricCheck(const std::string& text);

struct CheckResult {
  MetricCheck check;
  bool passed = false;
  std::string message;  ///< what was found, e.g. "tracking.final_error = 1.33e-05 (< 1e-04 holds)"
};

/// Each check against the run's summary (null when it could not be read).
std::vector<CheckResult> evaluateChecks(const std::vector<MetricCheck>& checks,
                                        const nlohmann::json& summary);

/// The JUnit XML of the results (one testsuite, one testcase per check,
/// a <failure> for each missed), for CI systems.
std::string junitXml(const std::string& scenario_name, const std::vector<CheckResult>& results,
                     double wall_time);

}  // namespace lagrange::tools
