#pragma once
/// @file
/// MuJoCo (Debian's libmujoco 2.2.2, C API) behind the engine seam
/// (plant/physics_engine.hpp): the arm in generalized coordinates, from the
/// MJCF plant/mujoco/mujoco_model.hpp writes, stepped by mj_step with the
/// integrator plant.mujoco_integrator names. The input torques go to
/// qfrc_applied (the links', or the rotors' for flexible joints, whose
/// springs are tendons of the model). Deterministic: the same inputs in the
/// same order give the same doubles, so inproc equals lockstep and a log
/// replays bit for bit.
///
/// MuJoCo's warnings are counted, not printed (its default handler would
/// write MUJOCO_LOG.TXT into the working directory); its alarm for a bad
/// qpos, qvel or qacc -- after which mj_step has reset the state to q = 0 --
/// and its warnings of a clamped mass matrix or dropped constraint rows make
/// the engine unsound(), so the run stops, named, as on ODE.

#include <memory>

#include "plant/physics_engine.hpp"

namespace lagrange::plant {

/// @throws std::invalid_argument for an arm without bodies (a robot kind
///         described for ODE only) or a model MuJoCo does not compile, naming it.
std::unique_ptr<PhysicsEngine> makeMujocoEngine(const EngineSetup& setup);

}  // namespace lagrange::plant
