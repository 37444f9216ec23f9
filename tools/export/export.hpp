#pragma once
/// @file
/// `lagrange export RUN [-o FILE]`: a run's log as one HDF5 file (RUN/run.h5
/// unless -o names another), readable by h5py, MATLAB's h5read and Julia's
/// HDF5.jl (docs/export.md):
///
///   /                       attributes: format, source, run_id, joint_names,
///                           scenario (the resolved YAML), summary (summary.json's text)
///   /PLANT_TRUTH/tick       int64 [samples]             the sample's tick
///   /PLANT_TRUTH/t          float64 [samples]           header.sim_time [s]
///   /PLANT_TRUTH/publish_utime  int64 [samples]         the run's clock [us]
///   /PLANT_TRUTH/q          float64 [samples, joints]   attribute units = "rad"
///   /ACTUATOR_STATE/xi      float64 [samples, stages, joints]
///   ...
///   /tracking/tick, t, q, q_desired, q_error, error_norm
///                           the true tracking error per tick, as Python's
///                           Run.tracking (tracking_export.hpp)
///
/// One group per per-tick channel of the log, one dataset per field
/// (transport/message_fields.hpp), one row per tick in tick order (the first
/// intact copy of each). Written in blocks as the log is read (at most 4096
/// rows a channel, or 32 MiB of values, held), so the memory is the ticks'
/// list and those blocks, not the log's size.

#include <string>
#include <vector>

#include "logs/log_reader.hpp"
#include "tools/subcommand.hpp"

namespace lagrange::tools {

struct HdfExport {
  std::string path;
  std::vector<std::pair<std::string, long long>> channels;  ///< rows written per channel
  std::vector<std::string> warnings;                        ///< what could not be exported as it was
  logs::LogScan scan;
};

/// Where the export goes when no file is named: beside the log, its name
/// with .h5 for .lcm (a run folder's is RUN/run.h5).
std::string defaultExportPath(const std::string& target);

/// Writes `out_file` (empty: defaultExportPath) from the run at `target` (a
/// run directory, or a run.lcm beside its summary.json and
/// config.resolved.yaml). Refuses to replace an existing file unless `force`.
/// @throws lagrange::BadInput (a missing log, an existing file), RuntimeFault (HDF5 failed).
HdfExport exportHdf5(const std::string& target, const std::string& out_file, bool force);

/// Declares `lagrange export` on the front end (tools/export/export_cli.cpp).
Subcommand addExportCommand(CLI::App& app);

}  // namespace lagrange::tools
