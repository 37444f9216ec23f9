#pragma once
/// @file
/// Reading a log for replay (tools/replay/replay.hpp): the recorded messages by
/// channel and tick, the scenario it carries, what could not be used and
/// where it was, and the helpers that compare recorded with replayed values
/// bit for bit.

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
#include "logs/log_event_reader.hpp"
#include "tools/replay/log_damage.hpp"
#include "tools/replay/replay.hpp"
#include "tools/replay/replay_fit.hpp"

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
  /// Byte offset of the event each kept message came from, by channel and tick.
  std::map<std::string, std::map<int64_t, long long>> offsets;
  LogDamage damage;    ///< what could not be used, and where
  logs::LogScan scan;  ///< what the reader skipped or could not read
  long long events = 0, undecodable = 0;
  bool truncated = false;  ///< the log ended inside an event (a run killed while writing, or a cut file)
};

/// The log, its scenario as replayed (with --set), what its own SCENARIO
/// gives its messages, and the warnings so far.
struct Opened {
  Recorded rec;
  config::Scenario scenario;                           ///< as replayed: the log's, changed by --set
  MessageShape logged_shape;                           ///< what the log's own SCENARIO gives its messages
  config::Mode logged_mode = config::Mode::kLockstep;  ///< how the run that wrote the log ran
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
    throw ReplayError(e.what(), result.warnings, e.kind());
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

/// What the log says of `channel` ticks `from`..`to` it holds no usable copy
/// of, "" when nothing (log_damage.hpp): a copy of them that is corrupt, or
/// damage between the copies it holds before and after them.
std::string whyLacking(const Recorded& rec, const std::string& channel, int64_t from, int64_t to);

/// "the event at byte N" of the kept `channel` message of `tick`, or "".
std::string whereIs(const Recorded& rec, const std::string& channel, int64_t tick);

/// `m`, the message of `channel` tick `tick` replay is about to use.
/// @throws ReplayError (bad input) if it does not hold what the log's own
/// SCENARIO gives (replay_fit.hpp): the log contradicts itself.
template <class Msg>
const Msg& fitting(const Opened& o, const Msg& m, const char* channel) {
  const std::string why = misfit(m, o.logged_shape);
  if (!why.empty()) {
    const std::string at = whereIs(o.rec, channel, m.header.tick);
    throw ReplayError("the log's " + std::string(channel) + " tick " + std::to_string(m.header.tick) +
                      (at.empty() ? "" : " (" + at + ")") + " does not fit the log's own SCENARIO: it " +
                      why + "; it is not used, and outputs before it were replayed");
  }
  return m;
}

/// The message of `tick` in `m`, checked (fitting). @throws ReplayError
/// naming the missing input of `output_channel` tick `output_tick`, and what
/// the log says of it (whyLacking).
template <class Map>
const typename Map::mapped_type& input(const Opened& o, const Map& m, int64_t tick, const char* channel,
                                       const char* output_channel, int64_t output_tick) {
  const auto it = m.find(tick);
  if (it == m.end()) {
    const std::string why = whyLacking(o.rec, channel, tick, tick);
    throw ReplayError(std::string("the log lacks ") + channel + " tick " + std::to_string(tick) +
                      ", an input of " + output_channel + " tick " + std::to_string(output_tick) +
                      (why.empty() ? "" : " (" + why + ")") + "; outputs before it were replayed");
  }
  return fitting(o, it->second, channel);
}

/// Checks that an input read from the log, `rows` x `columns` as the log's
/// own SCENARIO gives it, is what the replayed scenario takes: --set can
/// change the arm or the chain the log's inputs were made for.
/// @throws ReplayError (bad input) naming `what` and both sizes.
void requireTaken(Eigen::Index rows, Eigen::Index columns, Eigen::Index expected_rows,
                  Eigen::Index expected_columns, const std::string& what);

/// "tick K (t = T s): " -- where a divergence is.
std::string at(int64_t tick, double t);

/// The torque profile the plant applied over the period ending at `truth`,
/// as the sample itself says it was chosen (tools/replay/replay_plant.cpp).
/// @throws ReplayError when the log lacks it, it does not fit, or the
/// sample names no way it was chosen.
void chooseTorque(const Opened& o, const lagrange::plant_truth_t& truth, Eigen::MatrixXd& tau);

}  // namespace lagrange::tools::replay_log
