/// @file
/// `lagrange export`'s command line (tools/export/export.hpp).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "tools/export/export.hpp"
#include "util/error.hpp"
#include "util/terminal_text.hpp"

namespace lagrange::tools {

namespace {
struct ExportCommandLine {
  std::string target;
  std::string out_file;
  bool force = false;
  bool quiet = false;
};

int exportRun(const ExportCommandLine& o) {
  // An error ends in tools::dispatch: "lagrange export: ...", exit by its kind.
  const HdfExport e = exportHdf5(o.target, o.out_file, o.force);
  for (const std::string& w : e.warnings)
    std::cerr << "lagrange export: warning: " << util::terminalSafeLines(w) << "\n";
  for (const std::string& p : e.scan.problems())
    std::cerr << "lagrange export: warning: " << util::terminalSafeLines(p) << "\n";
  if (!o.quiet) {
    std::cout << "lagrange export: wrote " << e.path << ":";
    for (const auto& [channel, rows] : e.channels) std::cout << " " << channel << " (" << rows << " rows)";
    std::cout << "\n";
  }
  return kExitOk;
}
}  // namespace

Subcommand addExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportCommandLine>();
  CLI::App* cmd = app.add_subcommand("export", "Write a run as one HDF5 file");
  describeCommand(
      *cmd,
      "Write a run's log as one HDF5 file (one group per channel, one dataset per field, one row per tick; "
      "units and joint names as attributes, the resolved scenario and summary.json as root attributes, the "
      "tracking error per tick in /tracking), into the run's folder unless -o names another file, "
      "for h5py, MATLAB and Julia (docs/export.md)",
      {"lagrange export runs/rigid_2dof", "lagrange export runs/rigid_2dof -o rigid_2dof.h5"});
  // Named RUN, and its absence said by exportHdf5 (what was expected), not
  // CLI11's "target: Path does not exist".
  cmd->add_option("RUN", o->target, "A run directory (its run.lcm) or an LCM log file")->required();
  cmd->add_option("-o,--out", o->out_file,
                  "The HDF5 file to write (default: beside the log, RUN/run.h5 for a run folder)");
  cmd->add_flag("--force", o->force, "Replace the file if it exists");
  cmd->add_flag("-q,--quiet", o->quiet, "Print warnings and errors only");
  return {cmd, [o](const Invocation&) { return exportRun(*o); }};
}

}  // namespace lagrange::tools
