#pragma once
/// @file
/// The config sections of the controllers, as their own files register them
/// (controller/registry.hpp): config knows a controller type only through
/// what is registered here. A type's section is either per-joint parameters
/// alone (the baselines, a user's controller: read into
/// ControllerConfig::params) or a section of its own, read and written by
/// the functions it registers (the paper's controllers: gains, stages,
/// filter starts, kept in ControllerConfig::settings). `external` (a program
/// in the controller's place) is the one type config knows by itself: it is
/// a way of wiring the run, not a control law.

#include <any>
#include <functional>
#include <string>
#include <vector>

#include "config/joint_vector_key.hpp"

namespace YAML {
class Emitter;
}

namespace lagrange::config {

class MapReader;
struct Scenario;

/// One key of controller.*: a per-joint vector (a list of n numbers, or one
/// number for every joint).
using ControllerParam = JointVectorKey;

/// What the reader demands of a scenario for a registered type.
struct ControllerTraits {
  /// It regulates to a constant q_d: any other reference is refused.
  bool set_point = false;
  /// It reads measured joint rates: a scenario without a velocity sensor
  /// (sensors.velocity) is refused.
  bool measures_velocity = false;
  /// How messages name it when it drives elastic joints (robot.flexible), as
  /// "the flexible controller (eq. 830)"; empty: it drives rigid joints only,
  /// and a scenario with robot.flexible is refused.
  std::string elastic_joints_title;
};

/// A section the type reads and writes itself (both set, or neither).
struct ControllerSectionCodec {
  /// Reads controller.* of a scenario whose type is this one (the keys read
  /// before it -- robot, actuator, reference, sensors -- are in `s`) and
  /// returns what ControllerConfig::settings keeps. Fails through `ctl`
  /// (MapReader::fail) and ends with ctl.finish.
  std::function<std::any(MapReader& ctl, const Scenario& s)> read;
  /// Writes the section's keys after `type` (config.resolved.yaml), so that
  /// `read` gives back the same settings, bit for bit.
  std::function<void(YAML::Emitter& out, const Scenario& s)> write;
};

struct ControllerRegistration {
  std::string type;                     ///< controller.type
  std::vector<ControllerParam> params;  ///< per-joint keys, when `section` is empty
  ControllerTraits traits;
  ControllerSectionCodec section;
  /// Where the type is listed in messages and docs: lower first, then by name.
  int listing = 100;
};

/// Makes `type` a valid controller.type. A type with params only must run
/// with actuator.order 0 (the command is the joint torque). Called by
/// controller::registerControllerKind. @throws std::logic_error if `type` is
/// already taken, or a codec has one function without the other.
void registerControllerSection(ControllerRegistration registration);

/// The registration of a type; nullptr for `external` and unknown ones.
const ControllerRegistration* controllerRegistration(const std::string& type);

/// The traits of a registered type (defaults for external and unknown ones).
ControllerTraits controllerTraits(const std::string& type);

/// Every valid controller.type: by listing, then name (external listed at 30).
std::vector<std::string> controllerTypes();
/// The same for a message: "theorem1, cascaded, ... or set_point".
std::string controllerTypeList();

}  // namespace lagrange::config
