#pragma once
/// @file
/// The paper's controllers behind the Controller interface: theorem1
/// (eq. 90), cascaded (eq. 750, behind an integrator chain of order
/// actuator.order) and flexible (Corollary 3, eq. (83)). Each owns its
/// control model and reference, which the cores refer to.

#include <vector>

#include "controller/registry.hpp"

namespace lagrange::controller {

/// Their registry entries, registered from paper_controllers.cpp's static
/// initialiser (with their section's key rows); the tests look at them.
std::vector<ControllerKind> paperControllerKinds();

}  // namespace lagrange::controller
