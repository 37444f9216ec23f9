/// @file
/// What drives the arm: actuator (integrator chain, rate, saturation) and
/// controller (Theorem 1, cascaded, flexible) (config/scenario_sections.hpp).

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "config/controller_params.hpp"
#include "config/key_table.hpp"
#include "config/scenario_sections.hpp"

namespace lagrange::config::sections {

namespace {
// kp, kd, a, b: one positive number per joint (or one for all), for stage 0
// and for each stage of a cascade alike.
template <class Gains>
Fields<Gains> gainFields() {
  using namespace field;
  return {
      jointVector("kp", &Gains::kp, VectorRule().required().positiveOnly()),
      jointVector("kd", &Gains::kd, VectorRule().required().positiveOnly()),
      jointVector("a", &Gains::a, VectorRule().required().positiveOnly()),
      jointVector("b", &Gains::b, VectorRule().required().positiveOnly()),
  };
}

// Gains of n joints, read from `map` among its other keys.
template <class Gains>
Gains readGains(MapReader& map, int n, const Fields<Gains>& fields) {
  Gains g;
  g.kp = g.kd = g.a = g.b = Eigen::VectorXd::Zero(n);
  readFieldsAmongOthers(map, g, fields);
  return g;
}
}  // namespace

const Fields<controller::Theorem1Gains>& paperGainFields() {
  static const Fields<controller::Theorem1Gains> fields = gainFields<controller::Theorem1Gains>();
  return fields;
}
const Fields<controller::StageGains>& stageGainFields() {
  static const Fields<controller::StageGains> fields = gainFields<controller::StageGains>();
  return fields;
}

// actuator: the integrator chain between controller and joints, and its rate.
void readActuatorSection(MapReader& root, Scenario& s) {
  const int n = s.dof();
  s.actuator.rate = s.plant.publish_rate;
  if (root.has("actuator")) {
    MapReader act = root.map("actuator");
    s.actuator.order = act.integer("order", 0);
    s.actuator.rate = act.positive("rate", s.plant.publish_rate);
    const double steps = s.actuator.rate / s.plant.publish_rate;
    const double per_step = static_cast<double>(s.substepsPerTick()) / std::round(steps);
    if (steps < 1.0 - 1e-9 || std::abs(steps - std::round(steps)) > 1e-6 * steps)
      act.fail("rate", "expected a whole multiple of plant.publish_rate (" +
                           std::to_string(s.plant.publish_rate) + " Hz), got " +
                           std::to_string(s.actuator.rate) + " Hz");
    if (std::abs(per_step - std::round(per_step)) > 1e-9)
      act.fail("rate", "the actuator period 1/rate must be a whole multiple of plant.physics_step (" +
                           std::to_string(s.plant.physics_step) +
                           " s), so that the torque changes on a physics step");
    if (s.actuator.order < 0 || s.actuator.order > 4)
      act.fail("order", "expected an integrator-chain order from 0 (torque passes through) to 4, got " +
                            std::to_string(s.actuator.order));
    s.actuator.saturation = act.optionalVector("saturation", n, true, true);
    s.actuator.initial_state = Eigen::MatrixXd::Zero(s.actuator.order, n);
    if (act.has("initial_state")) {
      YAML::Node rows = act.child("initial_state");
      if (!rows.IsSequence() || static_cast<int>(rows.size()) != s.actuator.order)
        act.fail("initial_state", "expected a list of " + std::to_string(s.actuator.order) +
                                      " rows (xi_1 .. xi_m), each a list of " + std::to_string(n) +
                                      " numbers");
      for (int i = 0; i < s.actuator.order; ++i) {
        YAML::Node wrapper;
        wrapper["row"] = rows[i];
        MapReader row(wrapper, act.keyPath("initial_state") + "[" + std::to_string(i) + "]");
        s.actuator.initial_state.row(i) = row.vector("row", n, true, false).transpose();
        row.finish({"row"});
      }
    }
    act.finish(keysUnder("actuator"));
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
// A program on PATH, or "" when there is none.
std::string onPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate)) return candidate;
  }
  return "";
}

// type external: a program from outside the project takes the controller's
// place (docs/external_controllers.md). Its command is checked here, before
// anything starts; a relative path is taken from the scenario file's folder.
void readExternalController(MapReader& ctl, Scenario& s, const std::string& base_dir) {
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
  const YAML::Node command = ctl.child("command");
  if (!command.IsSequence() || command.size() == 0)
    ctl.fail("command",
             "expected the controller's command line as a list, e.g. [python3, my_pd.py, --kp, 100]");
  for (const YAML::Node& arg : command) {
    if (!arg.IsScalar()) ctl.fail("command", "expected every entry to be a string");
    s.controller.command.push_back(arg.as<std::string>());
  }
  const std::filesystem::path base = std::filesystem::absolute(base_dir.empty() ? "." : base_dir);
  s.controller.working_directory =
      ctl.has("working_directory") ? std::filesystem::absolute(base / ctl.text("working_directory")).string()
                                   : base.string();
  if (!std::filesystem::is_directory(s.controller.working_directory))
    ctl.fail("working_directory", "'" + s.controller.working_directory +
                                      "' is not a directory; expected the folder the command starts in");
  std::string& program = s.controller.command[0];
  if (program.find('/') != std::string::npos) {
    const std::filesystem::path resolved = std::filesystem::absolute(base / program).lexically_normal();
    if (access(resolved.c_str(), X_OK) != 0 || std::filesystem::is_directory(resolved))
      ctl.fail("command", "'" + program + "' does not exist or is not executable (looked for " +
                              resolved.string() + "); expected the controller's program");
    program = resolved.string();
  } else if (onPath(program).empty()) {
    ctl.fail("command", "'" + program +
                            "' is not a program on PATH; expected the controller's program (a "
                            "name on PATH, or a path relative to the scenario file)");
  }
  ctl.finish(keysUnder("controller", "external"));
}
}  // namespace

// controller: its type, gains, filter start, stages and motor rate source.
void readControllerSection(MapReader& root, Scenario& s, const std::string& base_dir) {
  const int n = s.dof();
  MapReader ctl = root.map("controller");
  s.controller.type = ctl.text("type");
  if (s.controller.type == "external") return readExternalController(ctl, s, base_dir);
  const std::vector<ControllerParam>* registered = registeredControllerParams(s.controller.type);
  if (!s.controller.isPaperType() && registered == nullptr)
    ctl.fail("type",
             "unknown controller type '" + s.controller.type + "'; expected: " + controllerTypeList());
  if (s.flexible && s.controller.type != "flexible")
    ctl.fail("type",
             "robot.flexible has elastic joints, which only the flexible controller (eq. 830) "
             "drives; expected: type flexible");
  if (registered) return readRegisteredController(ctl, s, *registered);
  if (s.controller.type == "flexible") {
    if (!s.flexible)
      ctl.fail("type",
               "the flexible controller needs an arm with elastic joints; expected a robot.flexible "
               "section (stiffness, rotor_inertia)");
    if (s.actuator.order != 0)
      ctl.fail("type",
               "the flexible controller commands the motor torque itself; expected actuator.order 0, got " +
                   std::to_string(s.actuator.order));
    if (!ctl.has("motor_rate"))
      ctl.fail("motor_rate",
               "missing; the paper does not say where q2' comes from: expected measured (the "
               "motor's rate sensor, robot.flexible.rate_sensor: true) or filtered (a dirty "
               "derivative of q2)");
    s.controller.motor_rate = ctl.choice("motor_rate", kMotorRateNames, "choice");
    if (s.controller.motor_rate == MotorRate::kMeasured && !s.flexible->rate_sensor)
      ctl.fail("motor_rate",
               "measured needs a motor rate sensor; expected robot.flexible.rate_sensor: true, "
               "or motor_rate: filtered");
    if (s.controller.motor_rate == MotorRate::kFiltered)
      s.controller.motor_rate_pole = ctl.has("motor_rate_pole") ? ctl.vector("motor_rate_pole", n, true, true)
                                                                : Eigen::VectorXd::Constant(n, 300.0);
    else if (ctl.has("motor_rate_pole"))
      ctl.fail("motor_rate_pole", "only motor_rate: filtered has a filter pole");
  } else if (ctl.has("motor_rate") || ctl.has("motor_rate_pole")) {
    ctl.fail(ctl.has("motor_rate") ? "motor_rate" : "motor_rate_pole", "only the flexible controller has it");
  }
  if (s.controller.type == "theorem1" && s.actuator.order != 0)
    ctl.fail("type",
             "the theorem1 controller drives torque directly (actuator.order 0), but actuator.order is " +
                 std::to_string(s.actuator.order) + "; expected: type cascaded for an integrator chain");
  if (s.controller.type == "cascaded" || s.controller.type == "flexible") {
    if (s.controller.type == "cascaded" && s.actuator.order < 1)
      ctl.fail("type",
               "the cascaded controller needs an integrator chain; expected actuator.order from 1 to 4");
    const int count = s.controller.type == "flexible" ? 2 : s.actuator.order;
    YAML::Node stages = ctl.child("stages");
    if (!stages.IsSequence() || static_cast<int>(stages.size()) != count)
      ctl.fail("stages", "expected a list of " + std::to_string(count) +
                             (s.controller.type == "flexible"
                                  ? " stages (xi_1 = K q2, xi_2 = K q2': m = 2), each {kp, kd, a, b}"
                                  : " stages (one per integrator, actuator.order), each {kp, kd, a, b}"));
    for (size_t i = 0; i < stages.size(); ++i) {
      MapReader st(stages[i], ctl.keyPath("stages") + "[" + std::to_string(i) + "]");
      s.controller.stages.push_back(readGains(st, n, stageGainFields()));
      controller::StageStart start;
      start.qc = Eigen::VectorXd::Zero(n);
      start.zeta =
          st.has("initial_zeta") ? st.vector("initial_zeta", n, true, false) : Eigen::VectorXd::Zero(n);
      if (st.has("initial_filter_state")) {
        if (st.child("initial_filter_state").IsScalar() &&
            st.child("initial_filter_state").Scalar() == "bumpless")
          start.bumpless = true;
        else
          start.qc = st.vector("initial_filter_state", n, true, false);
      }
      s.controller.stage_starts.push_back(start);
      st.finish(keysUnder("controller.stages[i]"));
    }
  } else if (ctl.has("stages")) {
    ctl.fail("stages", "only the cascaded and flexible controllers have stages");
  }
  s.controller.gains = readGains(ctl, n, paperGainFields());
  if (!ctl.has("initial_filter_state")) {
    s.controller.initial_filter_state = Eigen::VectorXd::Zero(n);
  } else if (ctl.child("initial_filter_state").IsScalar() &&
             ctl.child("initial_filter_state").Scalar() == "bumpless") {
    s.controller.initial_filter_state.reset();
  } else {
    s.controller.initial_filter_state = ctl.vector("initial_filter_state", n, true, false);
  }
  ctl.finish(keysUnder("controller", "paper"));
}

}  // namespace lagrange::config::sections
