/// @file
/// The plant process: stands in for the robot. Simulates the arm in ODE and
/// drives the clock of the run, in lockstep or realtime (plant_loops.hpp):
///
///   ACTUATOR_STATE -> PlantSim::step -> PLANT_POSITION (q), PLANT_TRUTH (q, q', energy)

#include <spdlog/spdlog.h>

#include "plant/plant_loops.hpp"
#include "plant/scenario_plant.hpp"
#include "runtime/process.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange {
namespace {

int DoMain(int argc, char** argv) {
  return runtime::runProcess(
      "plant", "The simulated robot arm (ODE or MuJoCo); drives the clock of the run.", argc, argv, {},
      nullptr, [&](const config::Scenario& s, transport::LcmNode& node) {
        plant::PlantSim sim = plant::plantFor(s);
        runtime::StatusReporter status(node);
        return s.mode == config::Mode::kRealtime ? plant::runRealtime(s, node, sim, status)
                                                 : plant::runLockstep(s, node, sim, status);
      });
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
