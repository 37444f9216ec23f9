#pragma once
/// @file
/// Replay of a controller from outside the project (controller.type external,
/// docs/external_controllers.md): there is no core to step, so its command
/// is started again, in a private network namespace on a bus of its own, and
/// fed the recorded PLANT_POSITION of each recorded command, in order, as the
/// plant would in lockstep; every answer is compared with the recorded one
/// bit for bit. A controller that keeps state sees the positions it answered
/// in the run, so lockstep logs replay; a realtime log does too when the
/// controller answered every position it received.

#include "tools/replay/replay.hpp"
#include "tools/replay/replay_log.hpp"

namespace lagrange::tools {

/// @throws ReplayError when the command cannot start or stops answering.
void replayExternalController(const replay_log::Opened& o, ReplayResult& result);

/// Whether the log's scenario names an external controller (its SCENARIO,
/// the log's first event, is all that is read): its replay needs a bus.
bool isExternalControllerLog(const std::string& log_path);

}  // namespace lagrange::tools
