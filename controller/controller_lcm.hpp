#pragma once
/// @file
/// CONTROL_COMMAND from a controller's output: one place, used by the
/// controller process, the in-process runner and the benchmarks alike.

#include <cstdint>

#include "controller/input_assembly.hpp"
#include "controller/theorem1.hpp"
#include "lagrange/control_command_t.hpp"

namespace lagrange::controller {

lagrange::control_command_t commandMessage(const Theorem1Output& out, int64_t position_tick, double sim_time,
                                           InputTicks inputs = {});

}  // namespace lagrange::controller
