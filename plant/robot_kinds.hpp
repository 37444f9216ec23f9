#pragma once
/// @file
/// The robot-kind seam: a kind is a model (model::RobotModel), an ODE
/// builder (plant::ArmBuilder) and the scenario section robot.<key> that
/// describes one arm. A new kind is its files and one registration:
///
///     const bool registered = lagrange::plant::registerRobotKind(
///         {{"my_arm", readMyArm, [](const std::any& a, double g) { return myArmModel(a, g); }, writeMyArm},
///          [](const std::any& a, double g) { return myArmWorld(a, g); }});
///
/// `robot: {my_arm: {...}}` then names it in a scenario: config reads and
/// writes its section (config/robot_kinds.hpp), the controllers, bounds and
/// reports take its model, and every wiring and replay build its plant here.
/// Every program of a run that reads the scenario must be built with the
/// file (docs/extending.md, "Adding a robot kind").

#include <any>
#include <functional>

#include "config/robot_kinds.hpp"
#include "config/scenario.hpp"
#include "plant/arm_world.hpp"
#include "plant/physics_engine.hpp"

namespace lagrange::plant {

struct RobotKind {
  config::RobotKindSection section;
  /// Its arm in the ODE world, from the settings its section read and robot.gravity.
  std::function<ArmBuilder(const std::any& settings, double gravity)> world;
};

/// Registers a kind (its section with config, its builder here). Returns
/// true, for a namespace-scope initialiser. @throws std::logic_error for a
/// key taken or a function missing.
bool registerRobotKind(RobotKind kind);

/// The builder of the scenario's arm: its registered kind's, the URDF arm's
/// or the planar chain's -- the one place the plant picks a kind.
ArmBuilder armBuilderFor(const config::Scenario& s);

/// Registers a physics engine (plant/physics_engine.hpp) under `key`: with
/// config, so that plant.engine accepts the key, and with the plant, which
/// builds it. Returns true, for a namespace-scope initialiser. @throws
/// std::logic_error for a key taken or a factory missing.
bool registerPhysicsEngine(const std::string& key, EngineFactory factory);

}  // namespace lagrange::plant
