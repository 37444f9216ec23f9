#pragma once
/// @file
/// The MJCF document of an arm, generated from what the project already
/// knows of it (plant/arm_world.hpp's ArmBodies): one nested body per link
/// with its hinge at the joint, its inertial at the centre of mass, and no
/// geometry (nothing collides; the viewer draws from ROBOT_DESCRIPTION).
/// Generalized coordinates: qpos is the joint angles themselves, continuous
/// over turns, and a joint cannot come apart.
///
///  - Flexible joints: a rotor body per joint on the base's z axis (inertia J_i
///    about it), and a fixed tendon q2_i - q1_i of stiffness K_i: the spring
///    is part of the model, so the integrator sees it within the step.
///  - Damping: the joint's `damping` (explicit under RK4, implicit under the
///    implicit and Euler integrators). Coulomb friction: `frictionloss`, a
///    constraint MuJoCo solves with the step. Stops: `range` (a soft
///    constraint, where ODE's are hard: a stop is the one place the two
///    engines are expected to differ). Both as stiff as MuJoCo advises.
///  - Every number is written with 17 significant digits, so each scalar
///    (mass, damping, stiffness, ...) is the scenario's double; positions are
///    written as differences of anchors and inertias turned to principal axes
///    by MuJoCo, so those agree to round-off, not bit for bit.
/// Pure: no MuJoCo call (plant/mujoco/mujoco_engine.cpp compiles it).

#include <optional>
#include <string>

#include "plant/physics_engine.hpp"

namespace lagrange::plant {

/// The MJCF text for `arm` with `setup`'s step, integrator, rotors and joint physics.
std::string mujocoModelXml(const ArmBodies& arm, const EngineSetup& setup);

}  // namespace lagrange::plant
