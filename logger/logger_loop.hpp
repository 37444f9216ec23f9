#pragma once
/// @file
/// The logger process's work (logger/main.cpp parses its options): record
/// every LCM channel of the run to run.lcm, compute the tracking metrics
/// live, confirm recorded ticks to the plant in STATUS
/// (logger::TickConfirmation), stop when the run has ended
/// (logger::RunEnd), and write summary.json.

#include <string>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "transport/lcm_node.hpp"

namespace lagrange::logger {

struct LoggerOptions {
  std::string out_dir = ".";  ///< where run.lcm and summary.json go
  double finish_grace = 2.0;  ///< [s] wait for the others' final STATUS after the plant finished
  int progress_fd = -1;       ///< "SIM_TIME ERROR" lines every 100 ms for the launcher; -1: none
};

/// `gains`: the scenario's gain report (controller::checkGains(s, false)),
/// computed or read before the run starts, with the launcher's sampled-data
/// check when it handed one (controller/gain_report_json.hpp); without one,
/// the check is made at the end, for summary.json. Returns the exit code; throws
/// lagrange::RuntimeFault if summary.json cannot be written.
int runLogger(const config::Scenario& s, transport::LcmNode& node, const LoggerOptions& options,
              controller::GainReport gains);

}  // namespace lagrange::logger
