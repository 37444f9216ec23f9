#pragma once
/// @file
/// The plant a scenario describes: one place that turns the config into a
/// PlantSim, for the plant process, the in-process runner and plant replay,
/// and the one place the plant picks the builder of the scenario's robot kind.

#include <optional>

#include "config/scenario.hpp"
#include "plant/joint_sensor.hpp"
#include "plant/plant_lcm.hpp"
#include "plant/plant_sim.hpp"

namespace lagrange::plant {

/// The arm of `s.robot` at `s.initial_state` (with rotors when s.flexible), stepping s.plant.physics_step,
/// with the joint damping, friction and stops the plant section asks for, in the engine plant.engine names.
PlantSim plantFor(const config::Scenario& s);

/// Builds the scenario's plant once and drops it, so that what an engine
/// refuses (an arm it cannot simulate) stops a run before anything starts.
/// @throws config::ConfigError with the engine's reason.
void checkPlantBuilds(const config::Scenario& s);

/// plant.engine and plant.mujoco_integrator, as the plant's engine seam takes them.
EngineChoice engineFor(const config::Scenario& s);

/// The joint damping, friction and stops of the scenario's plant: plant.joint_*
/// and plant.rotor_*, else (plant.urdf_dynamics) the URDF's <dynamics>, and
/// (plant.joint_limits) the URDF's <limit lower upper>. Empty when none.
JointPhysics jointPhysicsFor(const config::Scenario& s);

/// The scenario's sensors (sensors.*), one per measured quantity, each with
/// its own stream of draws from sensors.seed.
struct ScenarioSensors {
  JointSensor position;                 ///< PLANT_POSITION; ideal without sensors.position
  std::optional<JointSensor> velocity;  ///< PLANT_RATE: only with sensors.velocity
  std::optional<JointSensor> motor;     ///< PLANT_MOTOR's q2; ideal without sensors.motor
};
ScenarioSensors sensorsFor(const config::Scenario& s);

/// Everything the plant publishes at `tick` from the arm's state: positions
/// and truth, the motor sample of flexible joints, the velocity sensor's
/// rates when declared. Each sensor reads once: call it once per tick, in tick
/// order. The plant process, the in-process runner and plant replay all
/// measure through here, so every wiring publishes the same doubles.
PlantSample measureTick(const config::Scenario& s, ScenarioSensors& sensors, const PlantSim& sim,
                        int64_t tick, double sim_time, const Eigen::VectorXd& tau_applied, TorqueInput input);

}  // namespace lagrange::plant
