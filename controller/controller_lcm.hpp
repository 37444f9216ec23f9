#pragma once
/// @file
/// CONTROL_COMMAND from a controller's output: one place, used by the
/// controller process, the in-process runner and the benchmarks alike.

#include <cstdint>

#include "controller/theorem1.hpp"
#include "lagrange/control_command_t.hpp"

namespace lagrange::controller {

/// The ticks of the inputs a command was computed from (-1: a configured initial state, or none).
struct InputTicks {
  int64_t actuator = -1;
  int64_t motor = -1;
};

lagrange::control_command_t commandMessage(const Theorem1Output& out, int64_t position_tick, double sim_time,
                                           InputTicks inputs = {});

}  // namespace lagrange::controller
