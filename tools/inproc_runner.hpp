#pragma once
/// @file
/// The in-process wiring (`mode: inproc`): the same plant, actuator,
/// controller and metric cores as the LCM processes, called directly in one
/// process in the lockstep order, with no LCM traffic. It writes the same
/// run.lcm (the messages the processes would have published) and
/// summary.json, and its trajectories are bit-identical to lockstep runs.

#include <string>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"

namespace lagrange::tools {

class ProgressDisplay;

/// Runs the scenario; writes run.lcm and summary.json into out_dir.
/// Returns 0, or 130 when stop_requested() became true midway.
/// `gains`: the scenario's gain report, as the launcher already computed it
/// (the sampled-data check is not cheap), written into summary.json.
int runInProcess(const config::Scenario& scenario, const controller::GainReport& gains,
                 const std::string& out_dir, ProgressDisplay& progress, bool (*stop_requested)());

}  // namespace lagrange::tools
