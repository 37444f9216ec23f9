#pragma once
/// @file
/// The paper's controllers behind the Controller interface: theorem1
/// (eq. 90), cascaded (eq. 750, behind an integrator chain of order
/// actuator.order) and flexible (the Corollary, eq. 830). Each owns its
/// control model and reference, which the cores refer to.

#include <vector>

#include "controller/registry.hpp"

namespace lagrange::controller {

/// Their registry entries (registry.cpp seeds the registry with them).
std::vector<ControllerKind> paperControllerKinds();

}  // namespace lagrange::controller
