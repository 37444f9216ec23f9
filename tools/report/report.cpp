#include "tools/report/report.hpp"

#include <filesystem>
#include <iostream>
#include <limits>

#include "config/scenario.hpp"
#include "tools/report/tracking_table.hpp"
#include "transport/channels.hpp"
#include "util/terminal_text.hpp"

namespace lagrange::tools {

namespace {
// The plots' view of the run: from its scenario, else from the CSV columns.
PlotSpec specOf(const CsvExport& csv, const std::string& log_path, const std::string& out_dir,
                std::optional<config::Scenario>& scenario, std::vector<std::string>& warnings) {
  if (csv.scenario) {
    try {
      scenario = config::parseLoggedScenario(*csv.scenario, log_path + ":SCENARIO");
    } catch (const config::ConfigError& e) {
      warnings.push_back(std::string("the log's SCENARIO is not a valid scenario (") + e.what() +
                         "); the plots describe what the CSV columns show");
    }
  } else {
    warnings.push_back(
        "the log has no SCENARIO channel: plots are titled by the file name, without the "
        "tolerance line or timing histograms");
  }
  if (!scenario) return specFromCsv(out_dir, std::filesystem::path(log_path).filename().string());
  const config::Scenario& s = *scenario;
  PlotSpec spec;
  spec.dir = out_dir;
  spec.title = s.name + " (" + config::toString(s.mode) + ", " + s.controller.type + ")";
  spec.dof = s.dof();
  spec.chain_order = s.actuator.order;
  spec.flexible = s.flexible.has_value();
  spec.tolerance = s.metrics.tolerance;
  spec.joint_names = s.robotModel()->jointNames();
  if (s.urdf_model)
    for (const auto& joint : s.urdf_model->jointProperties())
      spec.velocity_limits.push_back(joint.velocity ? *joint.velocity
                                                    : std::numeric_limits<double>::infinity());
  return spec;
}
}  // namespace

Report writeReport(const std::string& log_path, const std::string& out_dir) {
  Report report;
  report.csv = exportCsv(log_path, out_dir);
  report.warnings = report.csv.scan.problems();
  if (report.csv.rows.empty())
    throw logs::LogError(
        log_path + " holds no message of this project among its " + report.csv.scan.describe() +
        " (expected PLANT_TRUTH, PLANT_POSITION, PLANT_MOTOR, CONTROL_COMMAND, ACTUATOR_STATE: a log "
        "of a lagrange run)");
  std::optional<config::Scenario> scenario;
  PlotSpec spec = specOf(report.csv, log_path, out_dir, scenario, report.warnings);
  const std::filesystem::path tracking_csv =
      std::filesystem::path(out_dir) / (std::string(kTrackingChannel) + ".csv");
  std::filesystem::remove(tracking_csv);  // a table of another log must not be plotted with this one
  // Only from this log's truth: a PLANT_TRUTH.csv of an earlier report in
  // the same folder is not this log's.
  if (scenario && report.csv.rows.count(transport::kPlantTruth) > 0) {
    const TrackingTable tracking = exportTracking(*scenario, out_dir);
    report.tracking_rows = tracking.rows;
    if (!tracking.problem.empty()) report.warnings.push_back(tracking.problem);
    if (tracking.skipped > 0)
      report.warnings.push_back(
          std::to_string(tracking.skipped) +
          " PLANT_TRUTH rows without a finite tick and time are left out of TRACKING.csv");
    if (tracking.rows > 0) {
      spec.convergence_time = tracking.convergence_time;
      spec.end_time = tracking.end_time;
    }
  }
  if (scenario) {
    const long long samples =
        report.csv.rows.count(transport::kPlantTruth) ? report.csv.rows.at(transport::kPlantTruth) : 0;
    if (samples < scenario->lastTick() + 1)
      report.warnings.push_back(
          "the log holds " + std::to_string(samples) + " of the run's " +
          std::to_string(scenario->lastTick() + 1) +
          " plant samples: the run was cut short (interrupted, a process died) or the log "
          "lost the rest");
  }
  if (scenario && scenario->mode == config::Mode::kRealtime)
    report.timing_rows = exportTiming(log_path, scenario->tickPeriod(), out_dir);
  try {
    report.plots = drawPlots(spec);
  } catch (const PlotError& e) {
    report.warnings.push_back(e.what());
  }
  if (!report.plots.failed.empty()) {
    std::string names;
    for (const auto& f : report.plots.failed) names += (names.empty() ? "" : ", ") + f;
    report.warnings.push_back("gnuplot could not draw " + names + "; its messages are in " +
                              report.plots.log);
  }
  return report;
}

void printReport(const Report& report, const std::string& out_dir, const std::string& prefix) {
  namespace fs = std::filesystem;
  for (const auto& [channel, n] : report.csv.rows)
    std::cout << prefix << n << " rows -> " << (fs::path(out_dir) / (channel + ".csv")).string() << "\n";
  if (report.tracking_rows > 0)
    std::cout << prefix << report.tracking_rows << " rows -> "
              << (fs::path(out_dir) / (std::string(kTrackingChannel) + ".csv")).string() << "\n";
  if (report.timing_rows > 0)
    std::cout << prefix << report.timing_rows << " rows -> "
              << (fs::path(out_dir) / (std::string(kTimingChannel) + ".csv")).string() << "\n";
  for (const auto& png : report.plots.written) std::cout << prefix << "plot -> " << png << "\n";
  for (const auto& w : report.warnings)
    std::cerr << prefix << "warning: " << util::terminalSafeLines(w) << "\n";
}

}  // namespace lagrange::tools
