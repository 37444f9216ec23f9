/// @file
/// The actuator process: stands in for the drives between controller and
/// robot. For order m = 0 the commanded torque passes through, optionally
/// saturated.
///
///   CONTROL_COMMAND -> validate -> IntegratorChain::step -> ACTUATOR_STATE

#include "actuator/actuator_lcm.hpp"
#include "actuator/integrator_chain.hpp"
#include "runtime/process.hpp"
#include "runtime/realtime_responder.hpp"
#include "runtime/tick_responder.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange {
namespace {

int DoMain(int argc, char** argv) {
  return runtime::runProcess(
      "actuator", "Actuator dynamics between controller and plant (order m = 0: pass-through).", argc, argv,
      {}, nullptr, [](const config::Scenario& s, transport::LcmNode& node) {
        actuator::IntegratorChain act(s.dof(), s.actuator.order, s.actuator.saturation,
                                      s.actuator.initial_state);
        const std::function<lagrange::actuator_state_t(const lagrange::control_command_t&)> compute =
            [&](const lagrange::control_command_t& m) {
              const actuator::ActuatorOutput out =
                  act.step(transport::toEigen(m.u), s.tickPeriod(), s.torqueStepsPerTick());
              return actuator::actuatorMessage(out, act.state(), m);
            };
        if (s.mode == config::Mode::kRealtime) {
          // Half a period after the plant: the controller has answered.
          return runtime::serveRealtime<lagrange::control_command_t, lagrange::actuator_state_t>(
              node, transport::kControlCommand, transport::kActuatorState, s.dof(),
              {s.tickPeriod(), 0.5, s.realtime.max_input_age},
              [&](const lagrange::control_command_t& m) { return std::optional(compute(m)); });
        }
        runtime::Progress progress;
        const auto last_state =
            runtime::respondPerTick<lagrange::control_command_t, lagrange::actuator_state_t>(
                node, transport::kControlCommand, transport::kActuatorState, s.dof(), progress,
                s.lockstep.logger_window + 2,  // the plant re-sends at most the unconfirmed window
                [&](const lagrange::control_command_t& m) { return std::optional(compute(m)); });
        // The plant re-sends a position nobody answered, and the controller
        // and this actuator answer a re-sent tick from their caches -- but a
        // controller waiting for the chain state of the previous tick (lost
        // on the way, or a restarted controller that never saw it) would wait
        // forever: re-send the last state whenever the run stalls.
        return runtime::serveUntilPlantFinished(
            node, progress,
            [&] {
              if (*last_state) node.publish(transport::kActuatorState, **last_state);
            },
            s.lockstep.retransmit_timeout);
      });
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
