#pragma once
/// @file
/// The planar chain (model/planar_chain.hpp) in ODE: one rigid body per link,
/// hinge joints about the z axis, gravity -g along y. Joint angles are read
/// from the bodies' absolute orientations (the relative angle of link i to
/// link i-1); joint torque tau_i acts +tau_i on link i and -tau_i on link i-1.

#include "model/planar_chain.hpp"
#include "plant/arm_world.hpp"

namespace lagrange::plant {

/// @throws std::invalid_argument for parameters model::PlanarChain refuses.
ArmBuilder planarChainWorld(const model::ChainParams& params);

/// The chain as bodies at q = 0 for the other engines: it hangs along -y,
/// hinges on z, gravity -g along y, each link's inertia I_i about all three
/// axes (as its ODE body; only z turns in the plane).
ArmBodies planarChainBodies(const model::ChainParams& params);

}  // namespace lagrange::plant
