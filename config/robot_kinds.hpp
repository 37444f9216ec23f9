#pragma once
/// @file
/// The config side of robot kinds registered outside config
/// (plant/robot_kinds.hpp): the section robot.<key> a kind reads, the model
/// it builds from it and how it writes the section back. The planar chain
/// (robot.preset, robot.links) and the URDF arm (robot.urdf) are config's own.

#include <yaml-cpp/yaml.h>

#include <any>
#include <functional>
#include <string>
#include <vector>

#include "model/robot_model.hpp"

namespace lagrange::config {

class MapReader;

struct RobotKindSection {
  std::string key;  ///< robot.<key>; one of robot.preset, links, urdf or a registered key per scenario
  /// Reads robot.<key> (a map; fails through `section`, ends with
  /// section.finish) into the settings the scenario keeps.
  std::function<std::any(MapReader& section)> read;
  /// The arm of those settings under `gravity` [m/s^2] (robot.gravity).
  /// @throws lagrange::BadInput for settings that make no arm (named as robot.<key>).
  std::function<model::RobotModelPtr(const std::any& settings, double gravity)> model;
  /// Writes the section's value (its map) so that `read` gives the same settings back.
  std::function<void(YAML::Emitter& out, const std::any& settings)> write;
};

/// From a static initialiser (plant::registerRobotKind does it).
/// @throws std::logic_error for a key taken (config's own included) or a
///         function missing.
void registerRobotKindSection(RobotKindSection kind);

/// The registration of robot.<key>; nullptr for config's own and unknown keys.
const RobotKindSection* robotKindSection(const std::string& key);

/// Every registered key, by name.
std::vector<std::string> robotKindKeys();

}  // namespace lagrange::config
