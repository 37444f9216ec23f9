#pragma once
/// @file
/// The plant a scenario describes: one place that turns the config into a
/// PlantSim, for the plant process, the in-process runner and plant replay,
/// and the one place the plant picks the builder of the scenario's robot kind.

#include "config/scenario.hpp"
#include "plant/plant_sim.hpp"
#include "plant/position_sensor.hpp"

namespace lagrange::plant {

/// The arm of `s.robot` at `s.initial_state` (with rotors when s.flexible), stepping s.plant.physics_step.
PlantSim plantFor(const config::Scenario& s);

/// The joint-angle sensor the scenario declares (sensors.*): ideal without one.
PositionSensor positionSensorFor(const config::Scenario& s);

}  // namespace lagrange::plant
