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

#include "controller/gain_report.hpp"
#include "controller/theorem1.hpp"
#include "transport/builders.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "transport/process.hpp"
#include "transport/realtime_responder.hpp"
#include "transport/tick_responder.hpp"

namespace lagrange {
namespace {

int DoMain(int argc, char** argv) {
  bool strict = false;
  return transport::runProcess(
      "controller", "Theorem 1 position-feedback tracking controller (eq. 90) over LCM.", argc, argv,
      [&](CLI::App& app) {
        app.add_flag("--strict", strict, "Refuse to start when the gain condition eq. (11) is violated");
      },
      [&](const config::Scenario& s, transport::LcmNode& node) {
        const controller::GainReport gains = controller::checkGains(s);
        if (gains.condition.holds) {
          spdlog::info("{}", controller::describe(gains));
        } else if (strict) {
          spdlog::error("{} (refusing to start: --strict)", controller::describe(gains));
          return 3;
        } else {
          spdlog::warn("{} (running anyway; --strict makes this an error)", controller::describe(gains));
        }

        const model::PlanarChain chain(s.robot);
        const model::Reference reference(s.reference);
        controller::Theorem1Controller ctl(chain, reference, s.controller.gains,
                                           s.controller.initial_filter_state);
        const std::function<lagrange::control_command_t(const lagrange::plant_position_t&)> compute =
            [&](const lagrange::plant_position_t& m) {
              const auto out = ctl.step(m.header.sim_time, transport::toEigen(m.q));
              return transport::commandMessage(out, m.header.tick, m.header.sim_time);
            };
        if (s.mode == "realtime") {
          // A quarter period after the plant: its position has arrived.
          return transport::serveRealtime(node, transport::kPlantPosition, transport::kControlCommand,
                                          s.dof(), {s.tickPeriod(), 0.25, s.realtime.max_input_age}, compute);
        }
        transport::Progress progress;
        transport::respondPerTick(node, transport::kPlantPosition, transport::kControlCommand, s.dof(),
                                  progress, compute);
        return transport::serveUntilPlantFinished(node, progress);
      });
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
