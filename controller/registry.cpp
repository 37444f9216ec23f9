#include "controller/registry.hpp"

#include <map>
#include <stdexcept>
#include <string>
#include <utility>

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

ControllerKind withTunable(ControllerKind kind, std::vector<TunableGain> tunable) {
  kind.tunable = std::move(tunable);
  return kind;
}

bool registerControllerKind(ControllerKind kind) {
  if (kinds().count(kind.type) != 0)
    throw std::logic_error("controller type '" + kind.type + "' is registered twice");
  // lagrange tune searches every registered controller's gains: a kind
  // without a range to search would fail there, far from its registration.
  if (kind.tunable.empty())
    throw std::logic_error("controller type '" + kind.type +
                           "' declares no tunable gain; expected at least one (ControllerKind::tunable)");
  for (const TunableGain& g : kind.tunable)
    if (g.name.empty() || !(g.lower > 0.0) || !(g.upper > g.lower) || !(g.fallback >= g.lower) ||
        !(g.fallback <= g.upper))
      throw std::logic_error("controller type '" + kind.type + "': tunable gain '" + g.name +
                             "' has range [" + std::to_string(g.lower) + ", " + std::to_string(g.upper) +
                             "] and fallback " + std::to_string(g.fallback) +
                             "; expected a name, 0 < lower < upper and lower <= fallback <= upper");
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

const std::vector<TunableGain>& tunableGains(const std::string& type) { return kindOf(type).tunable; }

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
