#pragma once
/// @file
/// The names plant.engine accepts: the built-in engines ("ode", "mujoco")
/// and those a program registers (plant::registerPhysicsEngine, which tells
/// config here), so that a scenario naming an engine this program lacks is
/// refused when it is read, before anything starts.

#include <string>
#include <vector>

namespace lagrange::config {

/// @throws std::logic_error for a name taken.
void registerPhysicsEngineKey(const std::string& key);
/// Built-in first, then the registered ones in the order they came.
std::vector<std::string> physicsEngineKeys();

}  // namespace lagrange::config
