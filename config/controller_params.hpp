#pragma once
/// @file
/// The config section of a controller registered outside this library
/// (controller/registry.hpp): its per-joint parameters, which the reader
/// reads into ControllerConfig::params and the writer writes back. The
/// paper's three controllers (theorem1, cascaded, flexible) have their own
/// sections, read in config/drive_sections.cpp.

#include <string>
#include <vector>

namespace lagrange::config {

/// One key of controller.*: a per-joint vector (a list of n numbers, or one
/// number for every joint).
struct ControllerParam {
  std::string key;
  bool positive = false;  ///< every entry > 0
  std::string doc;        ///< what it is, with its unit (error messages, docs)
};

/// What the reader demands of a scenario for a registered type.
struct ControllerTraits {
  /// It regulates to a constant q_d: any other reference is refused.
  bool set_point = false;
  /// It reads measured joint rates: a scenario without a velocity sensor
  /// (sensors.velocity) is refused.
  bool measures_velocity = false;
};

/// Makes `type` a valid controller.type with these keys (the actuator order
/// must be 0: the command is the joint torque). Called by
/// controller::registerControllerKind. @throws std::logic_error if `type` is
/// already taken.
void registerControllerParams(const std::string& type, std::vector<ControllerParam> params,
                              ControllerTraits traits = {});

/// The traits of a registered type (defaults for the paper's and unknown ones).
ControllerTraits controllerTraits(const std::string& type);

/// The keys of a registered type; nullptr for the paper's types and unknown ones.
const std::vector<ControllerParam>* registeredControllerParams(const std::string& type);

/// Every valid controller.type: the paper's three, then the registered ones.
std::vector<std::string> controllerTypes();
/// The same for a message: "theorem1, cascaded, ... or set_point".
std::string controllerTypeList();

}  // namespace lagrange::config
