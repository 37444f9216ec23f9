#pragma once
/// @file
/// `lagrange sweep`, one row: its scenario read, its gains checked (once per
/// distinct gain setting: the check does not depend on the initial state), run
/// in-process with no log, and reduced to the sweep table's row.

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "controller/gain_report.hpp"
#include "tools/sweep/sweep_plan.hpp"

namespace lagrange::tools {

/// The table's columns after the parameters, in order (docs/sweeps.md).
const std::vector<std::string>& resultColumns();

class SweepRunner {
 public:
  explicit SweepRunner(const SweepPlan& plan) : plan_(plan) {}
  /// The row's results (the parameter and result columns), or none when
  /// `stop_requested` stopped it midway. A scenario that cannot be read (the
  /// plan checked it) throws config::ConfigError.
  std::optional<nlohmann::ordered_json> run(const SweepRow& row, bool (*stop_requested)());
  /// The row of a run that could not be made: status "failed", the reason.
  nlohmann::ordered_json failedRow(const SweepRow& row, const std::string& why) const;

 private:
  const controller::GainReport& gainsOf(const config::Scenario& s);
  const SweepPlan& plan_;
  std::map<std::string, controller::GainReport> gains_;  // by the scenario without its initial state
};

}  // namespace lagrange::tools
