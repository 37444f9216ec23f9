#include "plant/scenario_plant.hpp"

#include "plant/planar_chain_world.hpp"
#include "plant/urdf_arm_world.hpp"

namespace lagrange::plant {

PlantSim plantFor(const config::Scenario& s) {
  return PlantSim(
      s.urdf_model ? urdfArmWorld(s.urdf_model) : planarChainWorld(s.robot),
      {s.initial_state.q, s.initial_state.qdot, s.initial_state.motor_q, s.initial_state.motor_qdot},
      s.plant.physics_step, s.flexible ? std::optional(s.flexible->params) : std::nullopt, s.plant.max_rate);
}

PositionSensor positionSensorFor(const config::Scenario& s) {
  if (!s.sensors) return PositionSensor(s.dof());
  return PositionSensor(
      s.dof(), {s.sensors->counts_per_revolution, s.sensors->noise_sigma, s.sensors->delay, s.sensors->seed});
}

}  // namespace lagrange::plant
