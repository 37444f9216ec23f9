#pragma once
/// @file
/// `lagrange report DIR|LOG` and `lagrange run --report`: CSV per channel
/// (csv_export.hpp) and PNG plots (plots.hpp) of a run's log, in one folder.

#include <string>
#include <vector>

#include "tools/report/csv_export.hpp"
#include "tools/report/plots.hpp"
#include "tools/subcommand.hpp"

namespace lagrange::tools {

struct Report {
  CsvExport csv;
  long long timing_rows = 0;          ///< TIMING.csv rows (realtime runs)
  long long tracking_rows = 0;        ///< TRACKING.csv rows (a log with its scenario)
  Plots plots;                        ///< PNGs written, and those gnuplot could not draw
  std::vector<std::string> warnings;  ///< what was not read, or not drawn, and why
};

/// @throws LogError when the log cannot be read or holds no message of this
///         project; RuntimeFault when a file cannot be written.
Report writeReport(const std::string& log_path, const std::string& out_dir);

/// Prints what `report` wrote, and its warnings, for a person.
void printReport(const Report& report, const std::string& out_dir, const std::string& prefix);

/// Declares `report` and its options on the front end (tools/report/report_cli.cpp).
Subcommand addReportCommand(CLI::App& app);

}  // namespace lagrange::tools
