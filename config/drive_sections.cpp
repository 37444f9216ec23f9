/// @file
/// What drives the arm: actuator (integrator chain, rate, saturation) and
/// controller -- its type, and the section its registration reads
/// (config/controller_params.hpp) (config/scenario_sections.hpp).

#include "config/controller_params.hpp"
#include "config/external_command.hpp"
#include "config/key_table.hpp"
#include "config/scenario_sections.hpp"
#include "config/work_bounds.hpp"
#include "model/urdf_arm.hpp"
#include "util/number_text.hpp"

namespace lagrange::config::sections {

namespace {
// actuator.initial_state: xi_1(0) .. xi_m(0), m = order rows of n numbers
// (initial_state's size says both when this is read).
void readChainState(MapReader& act, ActuatorConfig& a) {
  if (!act.has("initial_state")) return;
  const int m = static_cast<int>(a.initial_state.rows()), n = static_cast<int>(a.initial_state.cols());
  YAML::Node rows = act.child("initial_state");
  if (!rows.IsSequence() || static_cast<int>(rows.size()) != m)
    act.fail("initial_state", "expected a list of " + std::to_string(m) +
                                  " rows (xi_1 .. xi_m), each a list of " + std::to_string(n) + " numbers");
  for (int i = 0; i < m; ++i) {
    YAML::Node wrapper;
    wrapper["row"] = rows[i];
    MapReader row(wrapper, act.keyPath("initial_state") + "[" + std::to_string(i) + "]");
    a.initial_state.row(i) = row.vector("row", n, true, false).transpose();
    row.finish({"row"});
  }
}
}  // namespace

// actuator.order and rate: the chain and its clock, checked against the
// plant's before the rest is read (its sizes follow from the order).
const Fields<ActuatorConfig>& actuatorChainFields() {
  using namespace field;
  static const Fields<ActuatorConfig> fields = {
      {"order", [](MapReader& m, ActuatorConfig& a) { a.order = m.integer("order", a.order); },
       plainWriter("order", &ActuatorConfig::order)},
      positive("rate", &ActuatorConfig::rate),
  };
  return fields;
}

namespace {
// Whether `key` holds the word `urdf` (a value taken from the arm's URDF).
bool saysUrdf(MapReader& m, const std::string& key) {
  if (!m.has(key)) return false;
  const YAML::Node node = m.child(key);
  return node.IsScalar() && node.Scalar() == "urdf";
}
}  // namespace

// actuator.saturation and initial_state: per joint, and per integrator.
const Fields<ActuatorConfig>& actuatorDriveFields() {
  using field::writeVector;
  static const Fields<ActuatorConfig> fields = {
      {"saturation",
       [](MapReader& m, ActuatorConfig& a) {
         if (saysUrdf(m, "saturation"))
           return;  // the URDF's efforts, read with the arm (readActuatorSection)
         a.saturation = m.optionalVector("saturation", static_cast<int>(a.initial_state.cols()), true, true);
       },
       [](YAML::Emitter& out, const ActuatorConfig& a) {
         if (a.saturation) writeVector(out, "saturation", *a.saturation);
       }},
      {"initial_state", readChainState,
       [](YAML::Emitter& out, const ActuatorConfig& a) {
         if (a.order == 0) return;
         out << YAML::Key << "initial_state" << YAML::Value << YAML::BeginSeq;
         for (int i = 0; i < a.order; ++i) {
           out << YAML::Flow << YAML::BeginSeq;
           for (int j = 0; j < a.initial_state.cols(); ++j) out << a.initial_state(i, j);
           out << YAML::EndSeq;
         }
         out << YAML::EndSeq;
       }},
  };
  return fields;
}

namespace {
// actuator.saturation: urdf -- each joint's <limit effort>.
Eigen::VectorXd urdfEfforts(MapReader& act, const Scenario& s) {
  if (!s.urdf_model)
    act.fail("saturation",
             "`urdf` takes each joint's <limit effort> from the arm's URDF, and this arm has no "
             "URDF; expected a number or a list of " +
                 std::to_string(s.dof()) + " numbers [N m]");
  const auto& joints = s.urdf_model->jointProperties();
  const std::vector<std::string> names = s.urdf_model->jointNames();
  Eigen::VectorXd out(s.dof());
  for (size_t i = 0; i < joints.size(); ++i) {
    if (!joints[i].effort)
      act.fail("saturation",
               "`urdf`: joint '" + names[i] +
                   "' of the URDF has no <limit effort> (or 0); expected a number or a list of " +
                   std::to_string(s.dof()) + " numbers [N m] instead");
    out(static_cast<Eigen::Index>(i)) = *joints[i].effort;
  }
  return out;
}
}  // namespace

// actuator: the integrator chain between controller and joints, and its rate.
void readActuatorSection(MapReader& root, Scenario& s) {
  const int n = s.dof();
  s.actuator.rate = s.plant.publish_rate;
  if (root.has("actuator")) {
    MapReader act = root.map("actuator");
    readFieldsAmongOthers(act, s.actuator, actuatorChainFields());
    const double steps = s.actuator.rate / s.plant.publish_rate;
    if (s.plant.external() && std::abs(steps - 1.0) > 1e-9)
      act.fail("rate",
               "an external plant (plant.type external) applies one torque per period; expected "
               "actuator.rate left out or equal to plant.publish_rate (" +
                   util::exactText(s.plant.publish_rate) + " Hz)");
    const double per_step = static_cast<double>(s.substepsPerTick()) / std::round(steps);
    if (steps < 1.0 - 1e-9 || std::abs(steps - std::round(steps)) > 1e-6 * steps)
      act.fail("rate", "expected a whole multiple of plant.publish_rate (" +
                           std::to_string(s.plant.publish_rate) + " Hz), got " +
                           std::to_string(s.actuator.rate) + " Hz");
    if (std::abs(per_step - std::round(per_step)) > 1e-9)
      act.fail("rate", "the actuator period 1/rate must be a whole multiple of plant.physics_step (" +
                           std::to_string(s.plant.physics_step) +
                           " s), so that the torque changes on a physics step");
    if (s.actuator.order < 0 || s.actuator.order > kMaxActuatorOrder)
      act.fail("order", "expected an integrator-chain order from 0 (torque passes through) to " +
                            std::to_string(kMaxActuatorOrder) + ", got " + std::to_string(s.actuator.order));
    s.actuator.initial_state = Eigen::MatrixXd::Zero(s.actuator.order, n);
    if (saysUrdf(act, "saturation")) s.actuator.saturation = urdfEfforts(act, s);
    readFieldsAmongOthers(act, s.actuator, actuatorDriveFields());
    std::set<std::string> known = keysOf(actuatorChainFields());
    for (const std::string& key : keysOf(actuatorDriveFields())) known.insert(key);
    act.finish(known);
  }
}

namespace {

// The section of a controller registered outside config (controller/registry.hpp):
// its declared per-joint parameters, nothing else.
void readRegisteredController(MapReader& ctl, Scenario& s, const std::vector<ControllerParam>& params) {
  if (s.actuator.order != 0)
    ctl.fail("type", "a registered controller commands the joint torque; expected actuator.order 0, got " +
                         std::to_string(s.actuator.order));
  const ControllerTraits traits = controllerTraits(s.controller.type);
  if (traits.measures_velocity && s.plant.external())
    ctl.fail("type", s.controller.type +
                         " feeds back measured joint rates, and an external plant (plant.type external) "
                         "publishes joint angles only; expected a position-only controller");
  if (traits.measures_velocity && !s.velocitySensor())
    ctl.fail("type", s.controller.type +
                         " feeds back measured joint rates, and this scenario declares no velocity sensor; "
                         "expected a sensors.velocity section (e.g. sensors: {velocity: {noise_sigma: 0}}), "
                         "or a position-only controller");
  if (traits.set_point) {
    const bool constant =
        s.reference.type == model::ReferenceType::kSine && (s.reference.amplitude.array() == 0.0).all();
    if (!constant)
      ctl.fail("type", s.controller.type +
                           " regulates to a constant q_d; expected reference.type sine with amplitude 0 on "
                           "every joint (q_d = offset)");
  }
  std::set<std::string> known = {"type"};
  for (const ControllerParam& p : params) {
    s.controller.params[p.key] = ctl.vector(p.key, s.dof(), true, p.positive);
    known.insert(p.key);
  }
  ctl.finish(known);
}
}  // namespace

namespace {
// type external: a program from outside the project takes the controller's
// place (docs/external_programs.md). Its command is checked here, before
// anything starts; a relative path is taken from the scenario file's folder.
void readExternalController(MapReader& ctl, Scenario& s, const std::string& base_dir, bool check_programs) {
  if (s.actuator.order != 0)
    ctl.fail("type", "an external controller commands the joint torque; expected actuator.order 0, got " +
                         std::to_string(s.actuator.order));
  if (s.flexible)
    ctl.fail("type", "an external controller drives rigid joints only; this arm has robot.flexible");
  if (s.mode == Mode::kInproc)
    ctl.fail(
        "type",
        "an external controller runs as its own process over LCM; expected mode lockstep or realtime, got "
        "inproc");
  ExternalCommand external = readExternalCommand(ctl, base_dir, "controller", check_programs);
  s.controller.command = std::move(external.command);
  s.controller.working_directory = std::move(external.working_directory);
  ctl.finish(keysUnder("controller", "external"));
}
}  // namespace

// controller: its type, then the section its registration reads (or, for
// external, the command that takes the controller's place).
void readControllerSection(MapReader& root, Scenario& s, const std::string& base_dir, bool check_programs) {
  MapReader ctl = root.map("controller");
  s.controller.type = ctl.text("type");
  if (s.controller.type == "external") return readExternalController(ctl, s, base_dir, check_programs);
  const ControllerRegistration* registration = controllerRegistration(s.controller.type);
  if (registration == nullptr)
    ctl.fail("type",
             "unknown controller type '" + s.controller.type + "'; expected: " + controllerTypeList());
  if (s.flexible && registration->traits.elastic_joints_title.empty()) {
    std::string titles, types;
    for (const std::string& type : controllerTypes())
      if (const std::string title = controllerTraits(type).elastic_joints_title; !title.empty()) {
        titles += (titles.empty() ? "" : " or ") + title;
        types += (types.empty() ? "" : " or ") + type;
      }
    ctl.fail("type",
             "robot.flexible has elastic joints, which only " + titles + " drives; expected: type " + types);
  }
  if (registration->section.read) {
    s.controller.settings = registration->section.read(ctl, s);
    return;
  }
  readRegisteredController(ctl, s, registration->params);
}

}  // namespace lagrange::config::sections
