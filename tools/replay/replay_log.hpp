#pragma once
/// @file
/// Reading a log for replay (tools/replay/replay.hpp): the recorded messages by
/// channel and tick, the scenario it carries, and the helpers that compare
/// recorded with replayed values bit for bit.

#include <Eigen/Dense>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "controller/theorem1.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "tools/replay/replay.hpp"

namespace lagrange::tools::replay_log {

/// A log's messages. Maps hold one message per tick (the first copy:
/// lockstep re-sends are identical); the vectors too, in tick order.
struct Recorded {
  std::optional<std::string> scenario;
  std::map<int64_t, lagrange::plant_position_t> positions;
  std::map<int64_t, lagrange::actuator_state_t> actuator;
  std::map<int64_t, lagrange::plant_motor_t> motor;
  std::map<int64_t, lagrange::plant_rate_t> rates;
  std::vector<lagrange::control_command_t> commands;  // first copy of each tick, in tick order
  std::vector<lagrange::actuator_state_t> states;     // likewise
  std::vector<lagrange::plant_truth_t> truths;        // likewise
  std::map<int64_t, lagrange::control_command_t> commands_by_tick;
  long long events = 0, undecodable = 0;
  bool truncated = false;  ///< the log ended inside an event (a run killed while writing, or a cut file)
};

/// The log, its scenario (with overrides) and the warnings so far.
struct Opened {
  Recorded rec;
  config::Scenario scenario;
  ReplayResult result;
};

/// Reads the log and parses its SCENARIO. `outputs`: the channel whose
/// recorded messages will be compared. @throws ReplayError when the file is
/// not an LCM log, has no SCENARIO, an invalid one, or none of `outputs`.
Opened openLog(const std::string& log_path, const std::vector<std::string>& overrides,
               const std::string& outputs);

/// Opens the log and runs `body(opened, result)`; a ReplayError thrown by
/// the body (an input the log lacks) carries the log's warnings with it.
template <class Body>
ReplayResult replayWith(const std::string& log_path, const std::vector<std::string>& overrides,
                        const std::string& outputs, Body body) {
  const Opened o = openLog(log_path, overrides, outputs);
  ReplayResult result = o.result;
  try {
    body(o, result);
  } catch (const ReplayError& e) {
    throw ReplayError(e.what(), result.warnings);
  }
  return result;
}

/// The first field of a recorded CONTROL_COMMAND that differs from a
/// replayed command (an empty diagnostic compared as the zeros the
/// controller process sends), "" when every one matches bit for bit.
std::string commandDifference(const lagrange::control_command_t& rec, const controller::Theorem1Output& out);

/// "" when equal bit for bit (the same NaN matches, -0 and +0 differ), else
/// "FIELD[i]: recorded X, replayed Y" with both exact (%.17g).
std::string compare(const std::string& field, const std::vector<double>& recorded,
                    const Eigen::VectorXd& replayed);
std::string compare(const std::string& field, double recorded, double replayed);

/// The message of `tick` in `m`. @throws ReplayError naming the missing input
/// of `output_channel` tick `output_tick`.
template <class Map>
const typename Map::mapped_type& input(const Map& m, int64_t tick, const char* channel,
                                       const char* output_channel, int64_t output_tick) {
  const auto it = m.find(tick);
  if (it == m.end())
    throw ReplayError(std::string("the log lacks ") + channel + " tick " + std::to_string(tick) +
                      ", an input of " + output_channel + " tick " + std::to_string(output_tick) +
                      "; outputs before it were replayed");
  return it->second;
}

/// "tick K (t = T s): " -- where a divergence is.
std::string at(int64_t tick, double t);

}  // namespace lagrange::tools::replay_log
