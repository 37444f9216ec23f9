#pragma once
/// @file
/// The gain check, computed once per run. `lagrange run` checks the gains
/// before it starts anything (it prints the verdicts, --strict refuses on
/// them) and writes the report to OUT/gains.json; the controller and the
/// logger, which need the same report (controller.log, --strict, summary.json),
/// read it there instead of repeating the check: on a URDF arm behind a chain
/// it is seconds of CPU (the k_c and eta estimates), which each process spent
/// again before the first tick.
///
/// The file names the scenario it was computed for (FNV-1a of its resolved
/// YAML): a process whose scenario differs, or that cannot read the file,
/// checks the gains itself, so a stale or damaged file costs time, never a
/// wrong report. Every number is kept exactly (non-finite ones as "inf",
/// "-inf", "nan"), so the report read back is the report written.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "controller/gain_report.hpp"

namespace lagrange::controller {

/// The simulated sampled-data check as JSON (gains.json's `simulated`, and
/// summary.json's gains.sampled_simulation); non-finite numbers as text.
nlohmann::json sampledSimulationJson(const SampledSimulation& simulation);

/// The report as the JSON text of OUT/gains.json, for the scenario whose
/// resolved YAML (config::toYaml) is `scenario_yaml`.
std::string gainReportJson(const GainReport& report, const std::string& scenario_yaml);

struct HandedGainReport {
  std::optional<GainReport> report;  ///< set when the file is for this scenario and reads whole
  std::string why_not;               ///< otherwise: why it was not used, for the process's log
};

/// The report in `json_text` if it was computed for `scenario_yaml`.
HandedGainReport gainReportFromJson(const std::string& json_text, const std::string& scenario_yaml);

struct ProcessGainReport {
  /// Without the sampled-data check: what checkGains(s, false) gives.
  GainReport report;
  /// The launcher's sampled-data check (checkSampledData(s)), when its
  /// report has one: the logger's summary.json takes it from here.
  std::optional<SampledDataCheck> sampled;
  std::string note;  ///< "" when read from the launcher's file or none was named; else why it was not
};

/// What a process of the run needs: the launcher's report from `path` (its
/// --gains; "" when none was given), its sampled-data check apart; or, when
/// the file is missing, unreadable or for another scenario, checkGains(s,
/// false) itself, with `note` saying why.
ProcessGainReport processGainReport(const config::Scenario& scenario, const std::string& path);

}  // namespace lagrange::controller
