/// @file
/// The paper controllers' config section (controller/paper_section.hpp).
#include "controller/paper_section.hpp"

#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "config/yaml_reader.hpp"

namespace lagrange::controller {

namespace {
using config::MapReader;
using config::Scenario;
using config::field::writeVector;

// kp, kd, a, b: one positive number per joint (or one for all), for stage 0
// and for each stage of a cascade alike.
template <class Gains>
config::Fields<Gains> gainFields() {
  using namespace config::field;
  return {
      jointVector("kp", &Gains::kp, VectorRule().required().positiveOnly()),
      jointVector("kd", &Gains::kd, VectorRule().required().positiveOnly()),
      jointVector("a", &Gains::a, VectorRule().required().positiveOnly()),
      jointVector("b", &Gains::b, VectorRule().required().positiveOnly()),
  };
}

// Gains of n joints, read from `map` among its other keys.
template <class Gains>
Gains readGains(MapReader& map, int n, const config::Fields<Gains>& fields) {
  Gains g;
  g.kp = g.kd = g.a = g.b = Eigen::VectorXd::Zero(n);
  readFieldsAmongOthers(map, g, fields);
  return g;
}

// Where q2' comes from: flexible's motor_rate and motor_rate_pole; the
// other two have neither.
void readMotorRate(MapReader& ctl, const Scenario& s, PaperSettings& p) {
  const int n = s.dof();
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
    p.motor_rate = ctl.choice("motor_rate", kMotorRateNames, "choice");
    if (p.motor_rate == MotorRate::kMeasured && !s.flexible->rate_sensor)
      ctl.fail("motor_rate",
               "measured needs a motor rate sensor; expected robot.flexible.rate_sensor: true, "
               "or motor_rate: filtered");
    if (p.motor_rate == MotorRate::kFiltered)
      p.motor_rate_pole = ctl.has("motor_rate_pole") ? ctl.vector("motor_rate_pole", n, true, true)
                                                     : Eigen::VectorXd::Constant(n, 300.0);
    else if (ctl.has("motor_rate_pole"))
      ctl.fail("motor_rate_pole", "only motor_rate: filtered has a filter pole");
  } else if (ctl.has("motor_rate") || ctl.has("motor_rate_pole")) {
    ctl.fail(ctl.has("motor_rate") ? "motor_rate" : "motor_rate_pole", "only the flexible controller has it");
  }
}

// The stages of cascaded (one per integrator) and flexible (two).
void readStages(MapReader& ctl, const Scenario& s, PaperSettings& p) {
  const int n = s.dof();
  const std::string& type = s.controller.type;
  if (type == "cascaded" || type == "flexible") {
    if (type == "cascaded" && s.actuator.order < 1)
      ctl.fail("type",
               "the cascaded controller needs an integrator chain; expected actuator.order from 1 to 4");
    const int count = type == "flexible" ? 2 : s.actuator.order;
    YAML::Node stages = ctl.child("stages");
    if (!stages.IsSequence() || static_cast<int>(stages.size()) != count)
      ctl.fail("stages", "expected a list of " + std::to_string(count) +
                             (type == "flexible"
                                  ? " stages (xi_1 = K q2, xi_2 = K q2': m = 2), each {kp, kd, a, b}"
                                  : " stages (one per integrator, actuator.order), each {kp, kd, a, b}"));
    for (size_t i = 0; i < stages.size(); ++i) {
      MapReader st(stages[i], ctl.keyPath("stages") + "[" + std::to_string(i) + "]");
      p.stages.push_back(readGains(st, n, stageGainFields()));
      StageStart start;
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
      p.stage_starts.push_back(start);
      st.finish(config::keysUnder("controller.stages[i]"));
    }
  } else if (ctl.has("stages")) {
    ctl.fail("stages", "only the cascaded and flexible controllers have stages");
  }
}

std::any readPaperSection(MapReader& ctl, const Scenario& s) {
  const int n = s.dof();
  PaperSettings p;
  readMotorRate(ctl, s, p);
  if (s.controller.type == "theorem1" && s.actuator.order != 0)
    ctl.fail("type",
             "the theorem1 controller drives torque directly (actuator.order 0), but actuator.order is " +
                 std::to_string(s.actuator.order) + "; expected: type cascaded for an integrator chain");
  readStages(ctl, s, p);
  p.gains = readGains(ctl, n, paperGainFields());
  if (!ctl.has("initial_filter_state")) {
    p.initial_filter_state = Eigen::VectorXd::Zero(n);
  } else if (ctl.child("initial_filter_state").IsScalar() &&
             ctl.child("initial_filter_state").Scalar() == "bumpless") {
    p.initial_filter_state.reset();
  } else {
    p.initial_filter_state = ctl.vector("initial_filter_state", n, true, false);
  }
  ctl.finish(config::keysUnder("controller", "paper"));
  return p;
}

// How a filter starts: its state, or "bumpless".
void writeFilterStart(YAML::Emitter& out, const std::optional<Eigen::VectorXd>& qc) {
  if (qc)
    writeVector(out, "initial_filter_state", *qc);
  else
    out << YAML::Key << "initial_filter_state" << YAML::Value << "bumpless";
}

void writePaperSection(YAML::Emitter& out, const Scenario& s) {
  const PaperSettings& c = paperSettings(s);
  if (c.motor_rate)
    out << YAML::Key << "motor_rate" << YAML::Value << util::nameOf(kMotorRateNames, *c.motor_rate);
  if (c.motor_rate_pole.size() > 0) writeVector(out, "motor_rate_pole", c.motor_rate_pole);
  writeFields(out, c.gains, paperGainFields());
  writeFilterStart(out, c.initial_filter_state);
  if (c.stages.empty()) return;
  out << YAML::Key << "stages" << YAML::Value << YAML::BeginSeq;
  for (size_t i = 0; i < c.stages.size(); ++i) {
    out << YAML::BeginMap;
    writeFields(out, c.stages[i], stageGainFields());
    if (i < c.stage_starts.size()) {
      const StageStart& start = c.stage_starts[i];
      if (start.bumpless)
        out << YAML::Key << "initial_filter_state" << YAML::Value << "bumpless";
      else if (start.qc.size() != 0)
        writeVector(out, "initial_filter_state", start.qc);
      if (start.zeta.size() != 0) writeVector(out, "initial_zeta", start.zeta);
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void requirePaperType(const Scenario& s) {
  if (!isPaperType(s.controller.type))
    throw std::logic_error("controller::paperSettings: controller.type '" + s.controller.type +
                           "' is not one of the paper's");
}
}  // namespace

bool isPaperType(const std::string& type) {
  return type == "theorem1" || type == "cascaded" || type == "flexible";
}

const PaperSettings& paperSettings(const Scenario& s) {
  requirePaperType(s);
  static const PaperSettings defaults;
  if (!s.controller.settings.has_value()) return defaults;
  return std::any_cast<const PaperSettings&>(s.controller.settings);
}

PaperSettings& paperSettings(Scenario& s) {
  requirePaperType(s);
  if (!s.controller.settings.has_value()) s.controller.settings = PaperSettings{};
  return std::any_cast<PaperSettings&>(s.controller.settings);
}

config::ControllerSectionCodec paperSectionCodec() { return {readPaperSection, writePaperSection}; }

const config::Fields<Theorem1Gains>& paperGainFields() {
  static const config::Fields<Theorem1Gains> fields = gainFields<Theorem1Gains>();
  return fields;
}
const config::Fields<StageGains>& stageGainFields() {
  static const config::Fields<StageGains> fields = gainFields<StageGains>();
  return fields;
}

std::vector<config::KeyInfo> paperKeyRows() {
  using namespace config::keyrow;
  return {
      only("paper",
           row("controller.motor_rate", "`measured` or `filtered`", "required for `flexible`",
               "where q2' comes from (the paper does not say): `measured` reads the rate sensors (needs "
               "`robot.flexible.rate_sensor: true`), `filtered` estimates it as a s/(s + a) q2 (exact "
               "discretisation, estimate 0 at t = 0)")),
      only("paper",
           row("controller.motor_rate_pole", "vector or scalar > 0", "`300`",
               "a [1/s] of the `filtered` estimate; at 1 kHz, 300 converges on the shipped configs and 1000 "
               "diverges (see `flexible_2dof_filtered_rate.yaml`).",
               gain())),
      only("paper",
           row("controller.kp", "vector or scalar > 0", "required", "proportional gain [N m/rad].", gain())),
      only("paper", row("controller.kd", "vector or scalar > 0", "required",
                        "gain on the filter output θ [N m s/rad when b = a].", gain())),
      only("paper", row("controller.a", "vector or scalar > 0", "required", "filter pole [1/s].", gain())),
      only("paper", row("controller.b", "vector or scalar > 0", "required",
                        "filter gain [1/s]; θ = b s/(s + a) q̃.", gain())),
      only("paper",
           row("controller.initial_filter_state", "vector, scalar or `bumpless`", "zeros",
               "qc(0); `bumpless` sets qc(0) = −b q̃(0) at the first sample, so θ(0) = 0.", largeState())),
      only(
          "paper",
          row("controller.stages", "list of m maps (2 for `flexible`)", "required for `cascaded`, `flexible`",
              "per stage i = 1..m, `{kp, kd, a, b}`, each a vector or scalar > 0: kp_i [1/s], kd_i, a_i "
              "[1/s] (pole of the approximate differentiator of xi_i*), b_i; sigma_i = b_i kp_{i-1} "
              "(sigma_1 = 0) is derived.")),
      inside("controller.stages[i].a", "controller.stages", gain()),
      inside("controller.stages[i].b", "controller.stages", gain()),
      inside("controller.stages[i].kd", "controller.stages", gain()),
      inside("controller.stages[i].kp", "controller.stages", gain()),
      row("controller.stages[i].initial_filter_state", "vector, scalar or `bumpless`", "zeros",
          "qc_i(0) of stage i, as stage 0's `initial_filter_state`: `bumpless` sets qc_i(0) = −b_i "
          "xi_i*(0) − zeta_i(0) at the first sample, so theta_i(0) = 0. The default, zeros, gives "
          "theta_i(0) = b_i xi_i*(0), a first command of kd_i b_i xi_i* more (hundreds of N m on the "
          "shipped chain configs); kept as the default so that existing scenarios and logs replay "
          "unchanged.",
          largeState()),
      row("controller.stages[i].initial_zeta", "vector or scalar", "zeros", "zeta_i(0) of stage i.",
          largeState()),
  };
}

}  // namespace lagrange::controller
