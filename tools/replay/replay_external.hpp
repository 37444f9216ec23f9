#pragma once
/// @file
/// Replay of a controller (or plant, below) from outside the project (controller.type external,
/// docs/external_programs.md): there is no core to step, so a program is
/// started, in a private network namespace on a bus of its own, and fed the
/// recorded PLANT_POSITION of each recorded command, in order, as the plant
/// would in lockstep; every answer is compared with the recorded one bit for
/// bit. A controller that keeps state sees the positions it answered in the
/// run, so lockstep logs replay; a realtime log does too when the controller
/// answered every position it received.
///
/// The program is the one the user names on replay's command line, never the
/// command the log's SCENARIO holds: a log is a file from anywhere, and
/// running what it says would let it run anything as the user replaying it.

#include <string>
#include <vector>

#include "tools/replay/replay.hpp"
#include "tools/replay/replay_log.hpp"

namespace lagrange::tools {

/// Runs `command` (argv; its program a path or a name on PATH, started in the
/// current directory) as the log's controller. @throws ReplayError (bad input)
/// when `command` is empty -- naming the log's command, which is not run --,
/// (a runtime fault) when the program cannot start or stops answering.
void replayExternalController(const replay_log::Opened& o, ReplayResult& result,
                              const std::vector<std::string>& command);

/// The program a log's SCENARIO names in `section` ("controller", "plant"),
/// read as the YAML stands (nothing resolved, nothing run): its type (""
/// when the log has no readable SCENARIO; "simulated" for a plant section
/// without one) and, for an external one, its command.
struct LoggedController {
  std::string type;
  std::vector<std::string> command;
  bool external() const { return type == "external"; }
};
LoggedController loggedController(const std::string& log_path, const std::string& section = "controller");

/// Runs `command` as the log's plant (plant.type external): the replay is
/// the actuator and the logger, the program the plant, in lockstep. The
/// program starts from the scenario's initial state; the answer to each
/// tick k is the torque the log's PLANT_TRUTH k+1 says was applied over the
/// period (its torque_source; a realtime log's held and zeroed periods
/// too), and every PLANT_TRUTH and PLANT_POSITION the program publishes is
/// compared with the recorded one bit for bit (in a realtime log,
/// input_actuator_tick and torque_source say which answer arrived in time,
/// not what the plant did, and are not compared). @throws ReplayError as
/// replayExternalController does.
void replayExternalPlant(const replay_log::Opened& o, ReplayResult& result,
                         const std::vector<std::string>& command);

}  // namespace lagrange::tools
