#pragma once
/// @file
/// The controller process's loop, once it has its controller: every
/// PLANT_POSITION answered with a CONTROL_COMMAND from Controller::step on
/// the inputs controller::InputAssembly puts together -- per tick in
/// lockstep (a repeated tick gets the cached command, so the filter never
/// steps twice on one sample), the newest in realtime.

#include "config/scenario.hpp"
#include "controller/controller.hpp"
#include "transport/lcm_node.hpp"

namespace lagrange::controller {

/// Serves until the plant finishes (lockstep) or the process is stopped
/// (realtime); returns the process's exit code.
int serveController(const config::Scenario& s, transport::LcmNode& node, Controller& ctl);

}  // namespace lagrange::controller
