#include "tools/replay.hpp"

#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "actuator/integrator_chain.hpp"
#include "config/scenario.hpp"
#include "controller/scenario_controller.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "transport/builders.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange::tools {

namespace {

struct Recorded {
  std::optional<std::string> scenario;
  std::map<int64_t, lagrange::plant_position_t> positions;
  std::map<int64_t, lagrange::actuator_state_t> actuator;
  std::map<int64_t, lagrange::plant_motor_t> motor;
  std::vector<lagrange::control_command_t> commands;  // first copy of each tick, in log order
  std::vector<lagrange::actuator_state_t> states;     // likewise
  std::map<int64_t, lagrange::control_command_t> commands_by_tick;
  long long events = 0, undecodable = 0;
};

template <class T>
bool decode(const lcm::LogEvent& ev, T& out) {
  return out.decode(ev.data, 0, static_cast<int>(ev.datalen)) >= 0;
}

Recorded readLog(const std::string& path) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw ReplayError("cannot open " + path + " as an LCM log");
  Recorded r;
  std::map<int64_t, bool> commanded, stated;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    ++r.events;
    const std::string& ch = ev->channel;
    bool ok = true;
    if (ch == transport::kScenario) {
      if (!r.scenario) r.scenario = std::string(static_cast<const char*>(ev->data), ev->datalen);
    } else if (ch == transport::kPlantPosition) {
      lagrange::plant_position_t m;
      if ((ok = decode(*ev, m))) r.positions.emplace(m.header.tick, m);
    } else if (ch == transport::kActuatorState) {
      lagrange::actuator_state_t m;
      if ((ok = decode(*ev, m)) && !stated[m.header.tick]) {
        stated[m.header.tick] = true;
        r.actuator.emplace(m.header.tick, m);
        r.states.push_back(m);
      }
    } else if (ch == transport::kPlantMotor) {
      lagrange::plant_motor_t m;
      if ((ok = decode(*ev, m))) r.motor.emplace(m.header.tick, m);
    } else if (ch == transport::kControlCommand) {
      lagrange::control_command_t m;
      if ((ok = decode(*ev, m)) && !commanded[m.input_position_tick]) {
        commanded[m.input_position_tick] = true;
        r.commands.push_back(m);
        r.commands_by_tick.emplace(m.header.tick, m);
      }
    }
    if (!ok) ++r.undecodable;
  }
  return r;
}

std::string show(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// "" when equal bit for bit, else "FIELD[i]: recorded X, replayed Y".
std::string compare(const char* field, const std::vector<double>& recorded, const Eigen::VectorXd& replayed) {
  if (static_cast<Eigen::Index>(recorded.size()) != replayed.size())
    return std::string(field) + ": recorded " + std::to_string(recorded.size()) + " values, replayed " +
           std::to_string(replayed.size());
  for (size_t i = 0; i < recorded.size(); ++i)
    if (!(recorded[i] == replayed(static_cast<Eigen::Index>(i))))
      return std::string(field) + "[" + std::to_string(i) + "]: recorded " + show(recorded[i]) +
             ", replayed " + show(replayed(static_cast<Eigen::Index>(i)));
  return "";
}

std::string firstDifference(const lagrange::control_command_t& rec, const controller::Theorem1Output& out) {
  for (auto [field, values, replayed] :
       {std::tuple{"u", &rec.u, &out.u}, std::tuple{"q_desired", &rec.q_desired, &out.q_desired},
        std::tuple{"q_error", &rec.q_error, &out.q_error}, std::tuple{"theta", &rec.theta, &out.theta},
        std::tuple{"filter_state", &rec.filter_state, &out.filter_state}}) {
    const std::string d = compare(field, *values, *replayed);
    if (!d.empty()) return d;
  }
  if (static_cast<Eigen::Index>(rec.xi_error.size()) != out.xi_error.rows())
    return "xi_error: recorded " + std::to_string(rec.xi_error.size()) + " stages, replayed " +
           std::to_string(out.xi_error.rows());
  for (size_t i = 0; i < rec.xi_error.size(); ++i) {
    const std::string field = "xi_error[" + std::to_string(i) + "]";
    const std::string d =
        compare(field.c_str(), rec.xi_error[i], out.xi_error.row(static_cast<Eigen::Index>(i)).transpose());
    if (!d.empty()) return d;
  }
  return "";
}

template <class Map>
const typename Map::mapped_type& input(const Map& m, int64_t tick, const char* channel,
                                       int64_t command_tick) {
  const auto it = m.find(tick);
  if (it == m.end())
    throw ReplayError(std::string("the log lacks ") + channel + " tick " + std::to_string(tick) +
                      ", an input of CONTROL_COMMAND tick " + std::to_string(command_tick) +
                      "; commands before it were replayed");
  return it->second;
}

// The log, its scenario (with overrides) and the warnings so far.
struct Opened {
  Recorded rec;
  config::Scenario scenario;
  ReplayResult result;
};

// `outputs`: the channel whose recorded messages will be compared; none is an error.
Opened openLog(const std::string& log_path, const std::vector<std::string>& overrides,
               const std::string& outputs) {
  Opened o;
  o.rec = readLog(log_path);
  const Recorded& rec = o.rec;
  ReplayResult& result = o.result;
  result.events = rec.events;
  if (rec.undecodable > 0)
    result.warnings.push_back(std::to_string(rec.undecodable) +
                              " events could not be decoded as this project's messages and were skipped");
  if (!rec.scenario)
    throw ReplayError(log_path + ": no SCENARIO channel among " + std::to_string(rec.events) +
                      " events; expected a log written by lagrange run (its first event is the scenario)" +
                      (result.warnings.empty() ? "" : "; " + result.warnings.front()));
  try {
    o.scenario = config::parseScenario(*rec.scenario, log_path + ":SCENARIO", overrides);
  } catch (const config::ConfigError& e) {
    throw ReplayError(std::string("the log's SCENARIO is not a valid scenario: ") + e.what());
  }
  const size_t count = outputs == transport::kActuatorState ? rec.states.size() : rec.commands.size();
  if (count == 0)
    throw ReplayError(log_path + ": no " + outputs + " among " + std::to_string(rec.events) +
                      " events: nothing to compare");
  return o;
}

std::string at(int64_t tick, double t, const char* channel) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "tick %lld (t = %.6f s): %s.", static_cast<long long>(tick), t, channel);
  return buf;
}

}  // namespace

ReplayResult replayController(const std::string& log_path, const std::vector<std::string>& overrides) {
  const Opened o = openLog(log_path, overrides, transport::kControlCommand);
  const Recorded& rec = o.rec;
  const config::Scenario& s = o.scenario;
  ReplayResult result = o.result;
  controller::ScenarioController ctl(s);
  for (const auto& cmd : rec.commands) {
    const int64_t k = cmd.input_position_tick;
    const auto& position = input(rec.positions, k, transport::kPlantPosition, k);
    const Eigen::VectorXd q = transport::toEigen(position.q);
    controller::Theorem1Output out;
    if (ctl.flexible()) {
      Eigen::VectorXd q2 = s.initial_state.motor_q;
      std::optional<Eigen::VectorXd> q2dot;
      if (s.flexible->rate_sensor) q2dot = s.initial_state.motor_qdot;
      if (cmd.input_motor_tick >= 0) {
        const auto& motor = input(rec.motor, cmd.input_motor_tick, transport::kPlantMotor, k);
        q2 = transport::toEigen(motor.q);
        q2dot = transport::motorRates(motor);
      }
      out = ctl.stepFlexible(position.header.sim_time, q, q2, q2dot);
    } else {
      Eigen::MatrixXd xi = s.actuator.initial_state;
      if (ctl.order() > 0 && cmd.input_actuator_tick >= 0)
        xi =
            transport::toEigen(input(rec.actuator, cmd.input_actuator_tick, transport::kActuatorState, k).xi);
      out = ctl.step(position.header.sim_time, q, xi);
    }
    ++result.commands;
    const std::string d = firstDifference(cmd, out);
    if (!d.empty()) {
      result.divergence = at(k, position.header.sim_time, transport::kControlCommand) + d;
      break;
    }
  }
  return result;
}

ReplayResult replayActuator(const std::string& log_path, const std::vector<std::string>& overrides) {
  const Opened o = openLog(log_path, overrides, transport::kActuatorState);
  const Recorded& rec = o.rec;
  const config::Scenario& s = o.scenario;
  ReplayResult result = o.result;
  actuator::IntegratorChain act(s.dof(), s.actuator.order, s.actuator.saturation, s.actuator.initial_state);
  for (const auto& state : rec.states) {
    const int64_t k = state.input_command_tick;
    const auto& cmd = input(rec.commands_by_tick, k, transport::kControlCommand, state.header.tick);
    const actuator::ActuatorOutput out =
        act.step(transport::toEigen(cmd.u), s.tickPeriod(), s.torqueStepsPerTick());
    ++result.commands;
    std::string d = compare("u_commanded", state.u_commanded, transport::toEigen(cmd.u));
    if (d.empty() && static_cast<Eigen::Index>(state.tau_applied.size()) != out.tau.rows())
      d = "tau_applied: recorded " + std::to_string(state.tau_applied.size()) + " steps, replayed " +
          std::to_string(out.tau.rows());
    for (size_t i = 0; d.empty() && i < state.tau_applied.size(); ++i)
      d = compare(("tau_applied[" + std::to_string(i) + "]").c_str(), state.tau_applied[i],
                  out.tau.row(static_cast<Eigen::Index>(i)).transpose());
    for (size_t i = 0; d.empty() && i < state.xi.size(); ++i)
      d = compare(("xi[" + std::to_string(i) + "]").c_str(), state.xi[i],
                  act.state().row(static_cast<Eigen::Index>(i)).transpose());
    for (size_t j = 0; d.empty() && j < state.saturated.size(); ++j)
      if (state.saturated[j] != static_cast<int8_t>(out.saturated(static_cast<Eigen::Index>(j))))
        d = "saturated[" + std::to_string(j) + "]: recorded " + std::to_string(state.saturated[j]) +
            ", replayed " + std::to_string(out.saturated(static_cast<Eigen::Index>(j)));
    if (!d.empty()) {
      result.divergence = at(state.header.tick, state.header.sim_time, transport::kActuatorState) + d;
      break;
    }
  }
  return result;
}

}  // namespace lagrange::tools
