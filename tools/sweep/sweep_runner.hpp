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
#include "wiring/inproc_runner.hpp"

namespace lagrange::tools {

/// The table's columns after the parameters, in order (docs/sweeps.md).
const std::vector<std::string>& resultColumns();

class SweepRunner {
 public:
  /// `out_dir` and `self_exe`: where and with which lagrange binary a row of
  /// an external controller runs (`lagrange run --mode lockstep`, in
  /// OUT/external/row-N, removed once read unless the run failed).
  SweepRunner(const SweepPlan& plan, std::string out_dir = "", std::string self_exe = "")
      : plan_(plan), out_dir_(std::move(out_dir)), self_exe_(std::move(self_exe)) {}
  /// The row's results (the parameter and result columns), or none when
  /// `stop_requested` stopped it midway. A scenario that cannot be read (the
  /// plan checked it) throws config::ConfigError.
  std::optional<nlohmann::ordered_json> run(const SweepRow& row, bool (*stop_requested)());
  /// The row of a run that could not be made: status "failed", the reason.
  nlohmann::ordered_json failedRow(const SweepRow& row, const std::string& why) const;

 private:
  const controller::GainReport& gainsOf(const config::Scenario& s);
  // An external controller's row: the program over LCM, what its summary.json says.
  wiring::InProcessOutcome runExternal(const SweepRow& row, bool (*stop_requested)());
  const SweepPlan& plan_;
  std::string out_dir_, self_exe_;
  std::map<std::string, controller::GainReport> gains_;  // by the scenario without its initial state
  nlohmann::json external_verdict_;  // the verdict of the last external row's summary.json
};

}  // namespace lagrange::tools
