#pragma once
/// @file
/// ODE behind the engine seam (plant/physics_engine.hpp): the design's
/// engine, in maximal coordinates. The world of one robot kind's builder
/// (plant/arm_world.hpp), stepped by dWorldStep (the accurate stepper), no
/// damping and no angular-speed clamp.
///
/// Torques are re-applied before every step (ODE clears its force
/// accumulators after each step): joint torque tau_i acts +tau_i on link i and
/// -tau_i on its parent. Joint angles, which the bodies show modulo 2 pi, are
/// kept continuous (multi-turn): each step the wrapped angle is unwrapped
/// towards the angle predicted from the joint rate, so turns are counted
/// correctly as long as the rate is below pi / physics_step.
///
/// Flexible joints: one more body per joint, the rotor, hinged to the base on
/// the z axis with inertia J_i about it. Each step the spring torque
/// K_i (q2_i - q1_i) acts as joint torque on joint i and opposite on rotor i,
/// and the input tau_i acts on rotor i; the stator reaction goes to the base.
/// Damping, friction and stops are ODE motors and hinge stops inside the step
/// (plant/joint_effects.hpp).

#include <memory>

#include "plant/physics_engine.hpp"

namespace lagrange::plant {

/// @throws std::invalid_argument for joint physics ODE's motors refuse.
std::unique_ptr<PhysicsEngine> makeOdeEngine(const EngineSetup& setup);

}  // namespace lagrange::plant
