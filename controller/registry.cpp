#include "controller/registry.hpp"

#include <map>
#include <stdexcept>

namespace lagrange::controller {

namespace {
// A controller from outside the project (controller.type external): the
// launcher starts its command in the controller's place, and nothing here
// runs it. Its gains mean nothing to lagrange.
ControllerKind externalKind() {
  ControllerKind kind;
  kind.type = "external";
  kind.make = [](const config::Scenario&) -> std::unique_ptr<Controller> {
    throw std::logic_error(
        "an external controller runs as its own process (controller.command); there is no core to build");
  };
  kind.report = [](const config::Scenario& s, bool) {
    GainReport r;
    r.unchecked = "external controller (" + s.controller.command.front() +
                  "): a program from outside the project, whose law lagrange does not know";
    return r;
  };
  return kind;
}

// A function-local static, so that registrations from other files' static
// initialisers find it ready.
std::map<std::string, ControllerKind>& kinds() {
  static std::map<std::string, ControllerKind> all = [] {
    std::map<std::string, ControllerKind> builtin;
    builtin.emplace("external", externalKind());
    return builtin;
  }();
  return all;
}

const ControllerKind& kindOf(const std::string& type) {
  const auto it = kinds().find(type);
  if (it == kinds().end())
    throw std::logic_error("controller type '" + type + "' is not registered in this program");
  return it->second;
}
}  // namespace

bool registerControllerKind(ControllerKind kind) {
  if (kinds().count(kind.type) != 0)
    throw std::logic_error("controller type '" + kind.type + "' is registered twice");
  config::registerControllerSection({kind.type,
                                     kind.keys,
                                     {kind.set_point, kind.measures_velocity, kind.elastic_joints_title},
                                     kind.section,
                                     kind.listing});
  const std::string type = kind.type;
  kinds().emplace(type, std::move(kind));
  return true;
}

std::unique_ptr<Controller> makeController(const config::Scenario& s) {
  return kindOf(s.controller.type).make(s);
}

GainReport checkGains(const config::Scenario& s, bool sampled_data) {
  const ControllerKind& kind = kindOf(s.controller.type);
  if (kind.report) return kind.report(s, sampled_data);
  GainReport r;
  r.unchecked = "no stability condition is known for controller type '" + s.controller.type +
                "': its gains are not checked";
  return r;
}

InputAssembly makeInputAssembly(const config::Scenario& s, const Needs& needs) {
  const bool rates = s.flexible && s.flexible->rate_sensor;
  Eigen::MatrixXd initial_motor = Eigen::MatrixXd::Zero(rates ? 2 : 1, s.dof());
  if (s.flexible) {
    initial_motor.row(0) = s.initial_state.motor_q.transpose();
    if (rates) initial_motor.row(1) = s.initial_state.motor_qdot.transpose();
  }
  return InputAssembly(needs, s.actuator.initial_state, initial_motor);
}

}  // namespace lagrange::controller
