/// @file
/// The actuator process: stands in for the drives between controller and
/// robot. For order m = 0 the commanded torque passes through, optionally
/// saturated.
///
///   CONTROL_COMMAND -> validate -> PassthroughActuator::step -> ACTUATOR_STATE

#include "actuator/passthrough.hpp"
#include "transport/builders.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "transport/process.hpp"
#include "transport/tick_responder.hpp"

namespace lagrange {
namespace {

int DoMain(int argc, char** argv) {
  return transport::runProcess(
      "actuator", "Actuator dynamics between controller and plant (order m = 0: pass-through).", argc, argv,
      nullptr, [](const config::Scenario& s, transport::LcmNode& node) {
        const actuator::PassthroughActuator act(s.dof(), s.actuator.saturation);
        transport::Progress progress;
        transport::respondPerTick<lagrange::control_command_t, lagrange::actuator_state_t>(
            node, transport::kControlCommand, transport::kActuatorState, s.dof(), progress,
            [&](const lagrange::control_command_t& m) {
              return transport::actuatorMessage(act.step(transport::toEigen(m.u)), m);
            });
        return transport::serveUntilPlantFinished(node, progress);
      });
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
