#pragma once
/// @file
/// ROBOT_DESCRIPTION: the scenario's arm as a viewer draws it.

#include "config/scenario.hpp"
#include "lagrange/robot_description_t.hpp"

namespace lagrange::config {

/// The geometry of the scenario's robot model (RobotModel::geometry), with
/// its kind, joint names and whether its joints are flexible.
lagrange::robot_description_t robotDescriptionMessage(const Scenario& s);

}  // namespace lagrange::config
