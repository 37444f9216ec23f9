#include "tools/replay/replay.hpp"

#include "actuator/integrator_chain.hpp"
#include "config/scenario.hpp"
#include "controller/controller_lcm.hpp"
#include "controller/registry.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "plant/plant_lcm.hpp"
#include "tools/replay/replay_external.hpp"
#include "tools/replay/replay_gaps.hpp"
#include "tools/replay/replay_log.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange::tools {

using namespace replay_log;

std::string replay_log::commandDifference(const lagrange::control_command_t& rec,
                                          const controller::Theorem1Output& out) {
  const Eigen::Index n = out.u.size();
  // The diagnostics as the controller process publishes them (an empty one as zeros).
  const Eigen::VectorXd q_desired = controller::asPublished(out.q_desired, n),
                        q_error = controller::asPublished(out.q_error, n),
                        theta = controller::asPublished(out.theta, n),
                        filter_state = controller::asPublished(out.filter_state, n);
  for (auto [field, values, replayed] :
       {std::tuple{"u", &rec.u, &out.u}, std::tuple{"q_desired", &rec.q_desired, &q_desired},
        std::tuple{"q_error", &rec.q_error, &q_error}, std::tuple{"theta", &rec.theta, &theta},
        std::tuple{"filter_state", &rec.filter_state, &filter_state}}) {
    const std::string d = compare(field, *values, *replayed);
    if (!d.empty()) return d;
  }
  if (static_cast<Eigen::Index>(rec.xi_error.size()) != out.xi_error.rows())
    return "xi_error: recorded " + std::to_string(rec.xi_error.size()) + " stages, replayed " +
           std::to_string(out.xi_error.rows());
  for (size_t i = 0; i < rec.xi_error.size(); ++i) {
    const std::string field = "xi_error[" + std::to_string(i + 1) + "]";
    const std::string d =
        compare(field, rec.xi_error[i], out.xi_error.row(static_cast<Eigen::Index>(i)).transpose());
    if (!d.empty()) return d;
  }
  return "";
}

ReplayResult replayController(const std::string& log_path, const std::vector<std::string>& overrides,
                              const std::vector<std::string>& external_command) {
  return replayWith(
      log_path, overrides, transport::kControlCommand, [&](const Opened& o, ReplayResult& result) {
        const Recorded& rec = o.rec;
        const config::Scenario& s = o.scenario;
        if (s.controller.type == "external") return replayExternalController(o, result, external_command);
        if (!external_command.empty())
          throw ReplayError("the log's controller is '" + s.controller.type +
                            "', which replay builds itself; a command after -- replays an external "
                            "controller (controller.type external) only, and none was run");
        const std::unique_ptr<controller::Controller> ctl = controller::makeController(s);
        const controller::Needs needs = ctl->needs();
        const Eigen::Index joints = s.dof();
        const OutputSequence sequence = outputSequence(transport::kControlCommand, o.logged_mode);
        const lagrange::header_t* previous = nullptr;
        for (const auto& cmd : rec.commands) {
          requireNoGap(rec, transport::kControlCommand, sequence, previous, cmd.header, result.commands);
          previous = &cmd.header;
          fitting(o, cmd, transport::kControlCommand);
          const int64_t k = cmd.input_position_tick;
          const std::string of_tick = " tick " + std::to_string(k);
          const auto& position =
              input(o, rec.positions, k, transport::kPlantPosition, transport::kControlCommand, k);
          controller::ControllerInputs in;
          in.t = position.header.sim_time;
          in.q = transport::toEigen(position.q);
          requireTaken(in.q.size(), 1, joints, 1, "PLANT_POSITION" + of_tick + "'s q");
          if (needs.joint_rates) {  // the rate of the position's own tick (controller/input_assembly.hpp)
            in.qdot = transport::toEigen(
                input(o, rec.rates, k, transport::kPlantRate, transport::kControlCommand, k).qdot);
            requireTaken(in.qdot.size(), 1, joints, 1, "PLANT_RATE" + of_tick + "'s qdot");
          }
          if (needs.motor_angles) {  // the configured initial state until the first PLANT_MOTOR
            in.motor_q = s.initial_state.motor_q;
            if (needs.motor_rates) in.motor_qdot = s.initial_state.motor_qdot;
            if (cmd.input_motor_tick >= 0) {
              const auto& motor = input(o, rec.motor, cmd.input_motor_tick, transport::kPlantMotor,
                                        transport::kControlCommand, k);
              in.motor_q = transport::toEigen(motor.q);
              requireTaken(in.motor_q.size(), 1, joints, 1,
                           "PLANT_MOTOR tick " + std::to_string(cmd.input_motor_tick) + "'s q");
              if (needs.motor_rates) {
                in.motor_qdot = plant::motorRates(motor);
                if (!in.motor_qdot)
                  throw ReplayError("PLANT_MOTOR tick " + std::to_string(cmd.input_motor_tick) +
                                    " holds no motor rates, as the log's SCENARIO gives it; the scenario "
                                    "changed by --set has robot.flexible.rate_sensor, and its controller "
                                    "takes them: the log's inputs do not fit the changed scenario");
                requireTaken(in.motor_qdot->size(), 1, joints, 1,
                             "PLANT_MOTOR tick " + std::to_string(cmd.input_motor_tick) + "'s qdot");
              }
            }
          }
          if (needs.actuator_order > 0) {
            in.xi = s.actuator.initial_state;
            if (cmd.input_actuator_tick >= 0) {
              const auto& state = input(o, rec.actuator, cmd.input_actuator_tick, transport::kActuatorState,
                                        transport::kControlCommand, k);
              in.xi = transport::toEigen(state.xi);
              requireTaken(in.xi.rows(), in.xi.cols(), needs.actuator_order, joints,
                           "ACTUATOR_STATE tick " + std::to_string(cmd.input_actuator_tick) + "'s xi");
            }
          }
          const controller::ControllerCommand out = ctl->step(in);
          ++result.commands;
          const std::string d = commandDifference(cmd, out);
          if (!d.empty()) {
            result.divergence = at(k, position.header.sim_time) + transport::kControlCommand + "." + d;
            break;
          }
        }
      });
}

namespace {

// The first difference between a recorded ACTUATOR_STATE and the replayed
// chain's output and state; sizes compared before any row is read.
std::string actuatorDifference(const lagrange::actuator_state_t& state, const Eigen::VectorXd& u,
                               const actuator::ActuatorOutput& out, const Eigen::MatrixXd& xi) {
  std::string d = compare("u_commanded", state.u_commanded, u);
  if (d.empty() && static_cast<Eigen::Index>(state.tau_applied.size()) != out.tau.rows())
    d = "tau_applied: recorded " + std::to_string(state.tau_applied.size()) + " steps, replayed " +
        std::to_string(out.tau.rows());
  for (size_t i = 0; d.empty() && i < state.tau_applied.size(); ++i)
    d = compare("tau_applied[" + std::to_string(i + 1) + "]", state.tau_applied[i],
                out.tau.row(static_cast<Eigen::Index>(i)).transpose());
  if (d.empty() && static_cast<Eigen::Index>(state.xi.size()) != xi.rows())
    d = "xi: recorded " + std::to_string(state.xi.size()) + " stages, replayed " + std::to_string(xi.rows());
  for (size_t i = 0; d.empty() && i < state.xi.size(); ++i)
    d = compare("xi[" + std::to_string(i + 1) + "]", state.xi[i],
                xi.row(static_cast<Eigen::Index>(i)).transpose());
  if (d.empty() && static_cast<Eigen::Index>(state.saturated.size()) != out.saturated.size())
    d = "saturated: recorded " + std::to_string(state.saturated.size()) + " values, replayed " +
        std::to_string(out.saturated.size());
  for (size_t j = 0; d.empty() && j < state.saturated.size(); ++j)
    if (state.saturated[j] != static_cast<int8_t>(out.saturated(static_cast<Eigen::Index>(j))))
      d = "saturated[" + std::to_string(j + 1) + "]: recorded " + std::to_string(state.saturated[j]) +
          ", replayed " + std::to_string(out.saturated(static_cast<Eigen::Index>(j)));
  return d;
}

}  // namespace

ReplayResult replayActuator(const std::string& log_path, const std::vector<std::string>& overrides) {
  return replayWith(
      log_path, overrides, transport::kActuatorState, [&](const Opened& o, ReplayResult& result) {
        const Recorded& rec = o.rec;
        const config::Scenario& s = o.scenario;
        actuator::IntegratorChain act(s.dof(), s.actuator.order, s.actuator.saturation,
                                      s.actuator.initial_state);
        const OutputSequence sequence = outputSequence(transport::kActuatorState, o.logged_mode);
        const lagrange::header_t* previous = nullptr;
        for (const auto& state : rec.states) {
          requireNoGap(rec, transport::kActuatorState, sequence, previous, state.header, result.commands);
          previous = &state.header;
          fitting(o, state, transport::kActuatorState);
          const int64_t k = state.input_command_tick;
          const auto& cmd = input(o, rec.commands_by_tick, k, transport::kControlCommand,
                                  transport::kActuatorState, state.header.tick);
          const Eigen::VectorXd u = transport::toEigen(cmd.u);
          requireTaken(u.size(), 1, s.dof(), 1, "CONTROL_COMMAND tick " + std::to_string(k) + "'s u");
          const actuator::ActuatorOutput out = act.step(u, s.tickPeriod(), s.torqueStepsPerTick());
          ++result.commands;
          const std::string d = actuatorDifference(state, u, out, act.state());
          if (!d.empty()) {
            result.divergence =
                at(state.header.tick, state.header.sim_time) + transport::kActuatorState + "." + d;
            break;
          }
        }
      });
}

}  // namespace lagrange::tools
