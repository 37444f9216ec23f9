#pragma once
/// @file
/// `lagrange report LOG|DIR`, first part: one CSV file per channel of a run's
/// LCM log, one row per recorded message (first copy of each tick), columns
/// named after the message fields with the joint index (q[0], q[1], ...) and
/// the stage for chain arrays (xi_error[1][0]). Units are those of
/// lcmtypes/*.lcm. PNG plots are not made by this version.

#include <map>
#include <string>

namespace lagrange::tools {

/// Rows written per channel; the files are OUT_DIR/CHANNEL.csv.
/// @throws std::runtime_error if the log cannot be opened or a file cannot be written.
std::map<std::string, long long> exportCsv(const std::string& log_path, const std::string& out_dir);

}  // namespace lagrange::tools
