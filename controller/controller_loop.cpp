#include "controller/controller_loop.hpp"

#include "controller/controller_lcm.hpp"
#include "controller/registry.hpp"
#include "runtime/realtime_responder.hpp"
#include "runtime/tick_responder.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange::controller {

int serveController(const config::Scenario& s, transport::LcmNode& node, Controller& ctl) {
  const Needs needs = ctl.needs();
  // The measurements besides q that it declared, assembled per tick
  // (lockstep) or newest (realtime) by controller::InputAssembly.
  InputAssembly assembly = makeInputAssembly(s, needs);
  subscribeDeclaredInputs(node, needs,
                          {s.dof(), s.torqueStepsPerTick(), s.flexible && s.flexible->rate_sensor}, assembly);
  auto command = [&](const lagrange::plant_position_t& m,
                     const std::optional<AssembledInputs>& in) -> std::optional<lagrange::control_command_t> {
    if (!in) return std::nullopt;
    return commandMessage(ctl.step(in->inputs), m.header.tick, m.header.sim_time, in->ticks);
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
}

}  // namespace lagrange::controller
