/// @file
/// The controller process: stands in for the real-time controller of a robot
/// that measures joint positions only.
///
///   PLANT_POSITION -> validate -> Theorem1Controller::step -> CONTROL_COMMAND
///
/// It subscribes to PLANT_POSITION and STATUS only: nothing it reads carries a
/// velocity. Lockstep: one command per position tick; a repeated tick (the
/// plant re-sending after a timeout) is answered with the cached command, so
/// the filter never steps twice on one sample.

#include <spdlog/spdlog.h>

#include "controller/chain_state_buffer.hpp"
#include "controller/controller_lcm.hpp"
#include "controller/gain_report.hpp"
#include "controller/registry.hpp"
#include "runtime/process.hpp"
#include "runtime/realtime_responder.hpp"
#include "runtime/tick_responder.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange {
namespace {

int DoMain(int argc, char** argv) {
  bool strict = false;
  return runtime::runProcess(
      "controller",
      "Position-feedback tracking controller over LCM: Theorem 1 (eq. 90) or cascaded (eq. 750).", argc, argv,
      [&](CLI::App& app) {
        app.add_flag(
            "--strict", strict,
            "Refuse to start when an evaluated gain condition (eq. 11; eq. 632 for m = 1) is violated");
      },
      [&](const config::Scenario& s, transport::LcmNode& node) {
        // The launcher prints the sampled-data check; here it would only delay the first tick.
        const controller::GainReport gains = controller::checkGains(s, false);
        if (gains.holds()) {
          spdlog::info("{}", controller::describe(gains));
        } else if (strict) {
          spdlog::error("{} (refusing to start: --strict)", controller::describe(gains));
          return 3;
        } else {
          spdlog::warn("{} (running anyway; --strict makes this an error)", controller::describe(gains));
        }

        const std::unique_ptr<controller::Controller> ctl = controller::makeController(s);
        const controller::Needs needs = ctl->needs();
        // The actuator chain's state (cascaded controller): ACTUATOR_STATE of
        // tick k carries xi at t_{k+1}, what position k+1 is answered with.
        // Lockstep looks states up by tick; realtime uses the newest.
        controller::ChainStateBuffer by_tick(s.actuator.initial_state);
        Eigen::MatrixXd xi = s.actuator.initial_state;
        int64_t xi_valid_for = 0;  // the position tick the newest xi belongs to
        if (needs.actuator_order > 0) {
          node.subscribe<lagrange::actuator_state_t>(
              transport::kActuatorState,
              [&](const lagrange::actuator_state_t& a) {
                const std::string why = transport::validate(a, s.dof(), s.torqueStepsPerTick());
                if (!why.empty() || a.order == needs.actuator_order) return why;
                return "actuator order is " + std::to_string(a.order) + ", expected " +
                       std::to_string(needs.actuator_order);
              },
              [&](const lagrange::actuator_state_t& a) {
                const Eigen::MatrixXd state = transport::toEigen(a.xi);
                by_tick.put(a.header.tick + 1, state);
                if (a.header.tick + 1 <= xi_valid_for) return;  // not newer than what we have
                xi = state;
                xi_valid_for = a.header.tick + 1;
              });
        }
        // Flexible joints: PLANT_MOTOR of tick k goes with PLANT_POSITION k.
        // Kept by tick as rows [q2; q2'] (q2' only with a rate sensor).
        controller::ChainStateBuffer motor_by_tick;
        std::optional<Eigen::MatrixXd> newest_motor;
        int64_t newest_motor_tick = -1;
        if (needs.motor_angles) {
          const bool rates = s.flexible->rate_sensor;
          // Realtime, before the first PLANT_MOTOR: the configured initial motor state.
          newest_motor = Eigen::MatrixXd(rates ? 2 : 1, s.dof());
          newest_motor->row(0) = s.initial_state.motor_q.transpose();
          if (rates) newest_motor->row(1) = s.initial_state.motor_qdot.transpose();
          node.subscribe<lagrange::plant_motor_t>(
              transport::kPlantMotor,
              [&, rates](const auto& m) { return transport::validate(m, s.dof(), rates); },
              [&, rates](const lagrange::plant_motor_t& m) {
                Eigen::MatrixXd sample(rates ? 2 : 1, s.dof());
                sample.row(0) = transport::toEigen(m.q).transpose();
                if (rates) sample.row(1) = transport::toEigen(m.qdot).transpose();
                motor_by_tick.put(m.header.tick, sample);
                if (m.header.tick > newest_motor_tick)
                  newest_motor = sample, newest_motor_tick = m.header.tick;
              });
        }
        auto command = [&](const lagrange::plant_position_t& m, const Eigen::MatrixXd& chain_state,
                           const Eigen::MatrixXd* motor, controller::InputTicks inputs) {
          controller::ControllerInputs in;
          in.t = m.header.sim_time;
          in.q = transport::toEigen(m.q);
          if (needs.actuator_order > 0) in.xi = chain_state;
          if (motor) in.motor_q = motor->row(0).transpose();
          if (motor && needs.motor_rates) in.motor_qdot = motor->row(1).transpose();
          return controller::commandMessage(ctl->step(in), m.header.tick, m.header.sim_time, inputs);
        };
        if (s.mode == config::Mode::kRealtime) {
          // A quarter period after the plant: its position has arrived. The
          // newest chain state is used (latest-value semantics).
          return runtime::serveRealtime<lagrange::plant_position_t, lagrange::control_command_t>(
              node, transport::kPlantPosition, transport::kControlCommand, s.dof(),
              {s.tickPeriod(), 0.25, s.realtime.max_input_age}, [&](const lagrange::plant_position_t& m) {
                const controller::InputTicks inputs{needs.actuator_order > 0 ? xi_valid_for - 1 : -1,
                                                    needs.motor_angles ? newest_motor_tick : -1};
                return command(m, xi, needs.motor_angles ? &*newest_motor : nullptr, inputs);
              });
        }
        // Lockstep: answer position k only with the chain state of t_k; if
        // ACTUATOR_STATE k-1 has not arrived yet, stay silent: the plant
        // re-sends position k and it is answered then.
        runtime::Progress progress;
        runtime::respondPerTick<lagrange::plant_position_t, lagrange::control_command_t>(
            node, transport::kPlantPosition, transport::kControlCommand, s.dof(), progress,
            s.lockstep.logger_window + 2,  // the plant re-sends at most the unconfirmed window
            [&](const lagrange::plant_position_t& m) -> std::optional<lagrange::control_command_t> {
              if (needs.motor_angles) {
                const std::optional<Eigen::MatrixXd> motor = motor_by_tick.take(m.header.tick);
                if (!motor) return std::nullopt;  // PLANT_MOTOR k not here yet: the plant re-sends both
                return command(m, xi, &*motor, {-1, m.header.tick});
              }
              if (needs.actuator_order == 0) return command(m, xi, nullptr, {});
              const std::optional<Eigen::MatrixXd> state = by_tick.take(m.header.tick);
              if (!state) return std::nullopt;
              return command(m, *state, nullptr, {m.header.tick - 1, -1});  // tick 0: the initial state
            });
        return runtime::serveUntilPlantFinished(node, progress);
      });
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
