/// @file
/// The controller process: stands in for the real-time controller of a robot
/// that measures joint positions only.
///
///   PLANT_POSITION [+ ACTUATOR_STATE, PLANT_MOTOR, PLANT_RATE as the controller declares]
///     -> validate -> controller::InputAssembly -> Controller::step -> CONTROL_COMMAND
///
/// Besides PLANT_POSITION and STATUS it reads only what its needs() declare
/// (controller::subscribeDeclaredInputs).
/// Lockstep: one command per position tick; a repeated tick (the plant
/// re-sending after a timeout) is answered with the cached command, so the
/// filter never steps twice on one sample.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "controller/controller_lcm.hpp"
#include "controller/gain_report.hpp"
#include "controller/gain_report_json.hpp"
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
  std::string gains_path;
  controller::GainReport gains;
  return runtime::runProcess(
      "controller",
      "Position-feedback tracking controller over LCM: the scenario's controller.type (Theorem 1, eq. 90; "
      "cascaded, eq. 750; flexible, eq. 830; or a registered one).",
      argc, argv,
      {{"--strict", &strict,
        "Refuse to start when an evaluated gain condition (eq. 11; eq. 632 for m = 1) is violated"},
       {"--gains", &gains_path,
        "The launcher's gain report of this scenario (OUT/gains.json), instead of checking the gains again"}},
      // The launcher prints the sampled-data check; here it would only delay the first tick.
      [&](const config::Scenario& s) {
        controller::ProcessGainReport handed = controller::processGainReport(s, gains_path);
        if (!handed.note.empty()) spdlog::warn(fmt::format("{}", handed.note));
        gains = std::move(handed.report);
      },
      [&](const config::Scenario& s, transport::LcmNode& node) {
        if (!gains.holds() && strict) {
          spdlog::error(fmt::format("{} (refusing to start: --strict)", controller::describe(gains)));
          return 3;
        }
        const char* const running = gains.holds() ? "" : " (running anyway; --strict makes this an error)";
        spdlog::log(gains.holds() ? spdlog::level::info : spdlog::level::warn, "{}{}",
                    controller::describe(gains), running);

        const std::unique_ptr<controller::Controller> ctl = controller::makeController(s);
        const controller::Needs needs = ctl->needs();
        // The measurements besides q that it declared, assembled per tick
        // (lockstep) or newest (realtime) by controller::InputAssembly.
        controller::InputAssembly assembly = controller::makeInputAssembly(s, needs);
        controller::subscribeDeclaredInputs(
            node, needs, {s.dof(), s.torqueStepsPerTick(), s.flexible && s.flexible->rate_sensor}, assembly);
        auto command = [&](const lagrange::plant_position_t& m,
                           const std::optional<controller::AssembledInputs>& in)
            -> std::optional<lagrange::control_command_t> {
          if (!in) return std::nullopt;
          return controller::commandMessage(ctl->step(in->inputs), m.header.tick, m.header.sim_time,
                                            in->ticks);
        };
        if (s.mode == config::Mode::kRealtime) {
          // A quarter period after the plant: its position has arrived.
          return runtime::serveRealtime<lagrange::plant_position_t, lagrange::control_command_t>(
              node, transport::kPlantPosition, transport::kControlCommand, s.dof(),
              {s.tickPeriod(), 0.25, s.realtime.max_input_age}, [&](const lagrange::plant_position_t& m) {
                return command(m, assembly.newest(m.header.tick, m.header.sim_time, transport::toEigen(m.q)));
              });
        }
        // Lockstep: position k is answered only with the measurements of tick k;
        // until they are here it stays silent and the plant re-sends.
        runtime::Progress progress;
        runtime::respondPerTick<lagrange::plant_position_t, lagrange::control_command_t>(
            node, transport::kPlantPosition, transport::kControlCommand, s.dof(), progress,
            s.lockstep.logger_window + 2,  // the plant re-sends at most the unconfirmed window
            [&](const lagrange::plant_position_t& m) -> std::optional<lagrange::control_command_t> {
              return command(m, assembly.forTick(m.header.tick, m.header.sim_time, transport::toEigen(m.q)));
            });
        return runtime::serveUntilPlantFinished(node, progress);
      });
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
