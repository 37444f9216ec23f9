#pragma once
/// @file
/// `lagrange replay LOG --component controller|actuator|plant`. The controller: feeds its
/// recorded inputs -- PLANT_POSITION, and ACTUATOR_STATE / PLANT_MOTOR where
/// the scenario has them -- into a fresh controller core built from the
/// log's own SCENARIO, in the order the commands were recorded, and compares
/// every field of every recorded CONTROL_COMMAND bit for bit. Each command
/// names the ticks of the inputs it was computed from (input_position_tick,
/// input_actuator_tick, input_motor_tick), so lockstep and realtime logs
/// replay alike. Only the first copy of each tick is used (lockstep answers
/// a re-sent position from a cache, identically).

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/subcommand.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

/// A replay that could not be made. Bad input (the default): the log is
/// unreadable, has no SCENARIO, lacks an output or an input a command names
/// (a gap, or a copy that is corrupt), holds a message its own SCENARIO does
/// not give, or names an external controller no command was given for; the
/// message says what was still read. A runtime fault: what replays an
/// external controller failed (its network, its key, the program itself died
/// or went silent).
class ReplayError : public lagrange::Error {
 public:
  explicit ReplayError(const std::string& what, std::vector<std::string> warnings = {},
                       ErrorKind kind = ErrorKind::kBadInput)
      : lagrange::Error(kind, what), warnings_(std::move(warnings)) {}
  /// What else was wrong with the log (corrupt or missing bytes), found before this error.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  std::vector<std::string> warnings_;
};

struct ReplayResult {
  long long events = 0;                   ///< log events read
  long long commands = 0;                 ///< outputs replayed and compared
  std::optional<std::string> divergence;  ///< the first mismatch: tick, time, field, both values
  std::vector<std::string> warnings;      ///< e.g. undecodable events skipped
};

/// @param overrides "key=value" applied to the logged scenario (to test the test).
/// @param external_command the program that replays an external controller
/// (tools/replay/replay_external.hpp): named by the user, never read from the
/// log; must be empty for any other controller.
ReplayResult replayController(const std::string& log_path, const std::vector<std::string>& overrides = {},
                              const std::vector<std::string>& external_command = {});

/// The actuator: each recorded ACTUATOR_STATE from the CONTROL_COMMAND it
/// names (input_command_tick), through a fresh IntegratorChain; compares
/// u_commanded, every torque step, the chain state xi and the saturation flags.
ReplayResult replayActuator(const std::string& log_path, const std::vector<std::string>& overrides = {});

/// The plant: a fresh PlantSim stepped, period by period, with the torque
/// each recorded PLANT_TRUTH says was applied (input_actuator_tick and
/// torque_source: commanded, held or zero, so the stale-torque policy of a
/// realtime run replays too); compares q, q', the applied torque and the
/// energies of PLANT_TRUTH, q of PLANT_POSITION and q2 (q2') of PLANT_MOTOR.
/// @param external_command the program that replays an external plant
/// (plant.type external); must be empty for the simulated plant.
ReplayResult replayPlant(const std::string& log_path, const std::vector<std::string>& overrides = {},
                         const std::vector<std::string>& external_command = {});

/// Declares `replay` and its options on the front end (tools/replay/replay_cli.cpp).
Subcommand addReplayCommand(CLI::App& app);

}  // namespace lagrange::tools
