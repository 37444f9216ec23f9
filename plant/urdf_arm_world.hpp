#pragma once
/// @file
/// A URDF arm (model/urdf_arm.hpp) in ODE: one rigid body per moving link
/// (fixed-joint children and off-chain branches lumped into it, as the model
/// does) with its frame at the centre of mass and the URDF inertia tensor,
/// hinge joints on the URDF axes, gravity -g along the URDF world's z; joint
/// limits, damping and friction only as PlantSim adds them on the hinges
/// (plant/joint_effects.hpp). Joint angles
/// and rates are ODE's hinge readings; joint torque tau_i acts about axis i,
/// +tau_i on link i and -tau_i on its parent.
///
/// ODE keeps the bodies in maximal coordinates and holds the joints together
/// by constraint forces, so the links drift apart slightly over a run: the
/// drift is measured in tests/unit/urdf_plant_test.cpp and reported there.

#include <memory>
#include <vector>

#include "model/urdf_arm.hpp"
#include "plant/arm_world.hpp"

namespace lagrange::plant {

ArmBuilder urdfArmWorld(std::shared_ptr<const model::UrdfArm> arm);
/// The same arm with other bodies (a payload, model error: model/plant_perturbation.hpp).
ArmBuilder urdfArmWorld(std::vector<model::UrdfBody> bodies, double gravity);

}  // namespace lagrange::plant
