#pragma once
/// @file
/// `lagrange report LOG|DIR`, its tables: one CSV file per channel of a run's
/// LCM log, one row per recorded message (the first intact copy of each
/// tick), columns named after the message fields (transport/message_fields.hpp)
/// with the joint numbered from 1 (q[1], q[2], ...) and the stage or torque
/// step first for arrays of rows (xi_error[2][1]: stage 2, joint 1). Numbers
/// as the shortest text that reads back bit for bit. Units are those of
/// lcmtypes/*.lcm. For realtime runs also TIMING.csv, derived from the
/// messages' publish times.

#include <map>
#include <optional>
#include <string>

#include "logs/log_reader.hpp"

namespace lagrange::tools {

/// The derived table of a run's timing: tick, period_error_us (this sample's
/// publish time minus the previous one's, minus the period), command_latency_us
/// and actuator_latency_us (publish time of the CONTROL_COMMAND computed from
/// the sample, and of the ACTUATOR_STATE answering it, minus the sample's).
inline constexpr const char* kTimingChannel = "TIMING";

struct CsvExport {
  std::map<std::string, long long> rows;  ///< rows written per channel (OUT_DIR/CHANNEL.csv)
  std::optional<std::string> scenario;    ///< the log's SCENARIO text, if it has one
  logs::LogScan scan;                     ///< what was read, and what could not be
};

/// @throws LogError if the log cannot be read; RuntimeFault if a file cannot be written.
CsvExport exportCsv(const std::string& log_path, const std::string& out_dir);

/// Writes OUT_DIR/TIMING.csv for a run of tick `period` [s]; returns its rows (0: no PLANT_POSITION).
long long exportTiming(const std::string& log_path, double period, const std::string& out_dir);

}  // namespace lagrange::tools
