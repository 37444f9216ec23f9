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

ReplayResult replayController(const std::string& log_path, const std::vector<std::string>& overrides) {
  return replayWith(
      log_path, overrides, transport::kControlCommand, [&](const Opened& o, ReplayResult& result) {
        const Recorded& rec = o.rec;
        const config::Scenario& s = o.scenario;
        if (s.controller.type == "external") return replayExternalController(o, result);
        const std::unique_ptr<controller::Controller> ctl = controller::makeController(s);
        const controller::Needs needs = ctl->needs();
        for (const auto& cmd : rec.commands) {
          const int64_t k = cmd.input_position_tick;
          const auto& position =
              input(rec.positions, k, transport::kPlantPosition, transport::kControlCommand, k);
          controller::ControllerInputs in;
          in.t = position.header.sim_time;
          in.q = transport::toEigen(position.q);
          if (needs.joint_rates)  // the rate of the position's own tick (controller/input_assembly.hpp)
            in.qdot = transport::toEigen(
                input(rec.rates, k, transport::kPlantRate, transport::kControlCommand, k).qdot);
          if (needs.motor_angles) {  // the configured initial state until the first PLANT_MOTOR
            in.motor_q = s.initial_state.motor_q;
            if (needs.motor_rates) in.motor_qdot = s.initial_state.motor_qdot;
            if (cmd.input_motor_tick >= 0) {
              const auto& motor = input(rec.motor, cmd.input_motor_tick, transport::kPlantMotor,
                                        transport::kControlCommand, k);
              in.motor_q = transport::toEigen(motor.q);
              if (needs.motor_rates) in.motor_qdot = plant::motorRates(motor);
            }
          }
          if (needs.actuator_order > 0) {
            in.xi = s.actuator.initial_state;
            if (cmd.input_actuator_tick >= 0)
              in.xi = transport::toEigen(input(rec.actuator, cmd.input_actuator_tick,
                                               transport::kActuatorState, transport::kControlCommand, k)
                                             .xi);
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

ReplayResult replayActuator(const std::string& log_path, const std::vector<std::string>& overrides) {
  return replayWith(
      log_path, overrides, transport::kActuatorState, [&](const Opened& o, ReplayResult& result) {
        const Recorded& rec = o.rec;
        const config::Scenario& s = o.scenario;
        actuator::IntegratorChain act(s.dof(), s.actuator.order, s.actuator.saturation,
                                      s.actuator.initial_state);
        for (const auto& state : rec.states) {
          const int64_t k = state.input_command_tick;
          const auto& cmd = input(rec.commands_by_tick, k, transport::kControlCommand,
                                  transport::kActuatorState, state.header.tick);
          const actuator::ActuatorOutput out =
              act.step(transport::toEigen(cmd.u), s.tickPeriod(), s.torqueStepsPerTick());
          ++result.commands;
          std::string d = compare("u_commanded", state.u_commanded, transport::toEigen(cmd.u));
          if (d.empty() && static_cast<Eigen::Index>(state.tau_applied.size()) != out.tau.rows())
            d = "tau_applied: recorded " + std::to_string(state.tau_applied.size()) + " steps, replayed " +
                std::to_string(out.tau.rows());
          for (size_t i = 0; d.empty() && i < state.tau_applied.size(); ++i)
            d = compare("tau_applied[" + std::to_string(i + 1) + "]", state.tau_applied[i],
                        out.tau.row(static_cast<Eigen::Index>(i)).transpose());
          for (size_t i = 0; d.empty() && i < state.xi.size(); ++i)
            d = compare("xi[" + std::to_string(i + 1) + "]", state.xi[i],
                        act.state().row(static_cast<Eigen::Index>(i)).transpose());
          for (size_t j = 0; d.empty() && j < state.saturated.size(); ++j)
            if (state.saturated[j] != static_cast<int8_t>(out.saturated(static_cast<Eigen::Index>(j))))
              d = "saturated[" + std::to_string(j + 1) + "]: recorded " + std::to_string(state.saturated[j]) +
                  ", replayed " + std::to_string(out.saturated(static_cast<Eigen::Index>(j)));
          if (!d.empty()) {
            result.divergence =
                at(state.header.tick, state.header.sim_time) + transport::kActuatorState + "." + d;
            break;
          }
        }
      });
}

}  // namespace lagrange::tools
