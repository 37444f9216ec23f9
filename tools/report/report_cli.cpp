/// @file
/// `lagrange report`'s command line (tools/report/report.hpp).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>

#include "tools/report/report.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

namespace {
struct ReportCommandLine {
  std::string target;
  std::string out_dir;
};

int report(const ReportCommandLine& o) {
  namespace fs = std::filesystem;
  std::error_code not_a_directory;
  const std::string log_path =
      fs::is_directory(o.target, not_a_directory) ? (fs::path(o.target) / "run.lcm").string() : o.target;
  const std::string out_dir =
      o.out_dir.empty() ? (fs::path(log_path).parent_path() / "report").string() : o.out_dir;
  // An error ends in tools::dispatch: "lagrange report: ...", exit by its kind.
  printReport(writeReport(log_path, out_dir), out_dir, "lagrange report: ");
  return kExitOk;
}
}  // namespace

Subcommand addReportCommand(CLI::App& app) {
  auto o = std::make_shared<ReportCommandLine>();
  CLI::App* cmd = app.add_subcommand("report", "Write a run's CSV tables and PNG plots");
  describeCommand(
      *cmd,
      "Write one CSV file per channel of a run's log (rows: first copy of each tick; columns: the "
      "message fields per joint) and PNG plots drawn by gnuplot (tracking error, joints, torques, filter, "
      "actuator and, for realtime runs, timing histograms)",
      {"lagrange report runs/rigid_2dof"});
  cmd->add_option("target", o->target, "A run directory (its run.lcm) or an LCM log file")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("-o,--out", o->out_dir,
                  "Directory for the CSV files, plots and plots.gp (default: report/ next to the log)");
  return {cmd, [o](const Invocation&) { return report(*o); }};
}

}  // namespace lagrange::tools
