#include "config/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "config/yaml_reader.hpp"

namespace lagrange::config {

int Scenario::substepsPerTick() const {
  return static_cast<int>(std::llround(tickPeriod() / plant.physics_step));
}

int Scenario::torqueStepsPerTick() const {
  return actuator.rate > 0.0 ? static_cast<int>(std::llround(actuator.rate / plant.publish_rate)) : 1;
}

model::ChainParams Scenario::controlModel() const {
  model::ChainParams p = robot;
  if (flexible) p.joint_stiffness = flexible->params.stiffness;
  return p;
}

long long Scenario::lastTick() const { return std::llround(duration * plant.publish_rate); }

namespace {

// --set a.b.c=value: value is YAML ("[1, 2]", "0.5", "smooth_sine").
void applyOverride(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("config: --set '" + assignment + "': expected key=value, e.g. controller.kp=50");
  const std::string key = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw ConfigError("config: --set " + key + ": the value is not valid YAML: " + e.msg);
  }
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
  // Rebuild the path node by node; yaml-cpp nodes are references, so
  // assigning to the last one edits the tree in place.
  std::vector<YAML::Node> chain{root};
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node next = chain.back()[parts[i]];
    if (!next.IsDefined() || next.IsNull()) {
      chain.back()[parts[i]] = YAML::Node(YAML::NodeType::Map);
      next = chain.back()[parts[i]];
    }
    if (!next.IsMap()) throw ConfigError("config: --set " + key + ": '" + parts[i] + "' is not a map");
    chain.push_back(next);
  }
  chain.back()[parts.back()] = value;
}

model::ChainParams readRobot(MapReader robot) {
  model::ChainParams params;
  const bool has_preset = robot.has("preset");
  const bool has_links = robot.has("links");
  if (has_preset == has_links)
    robot.fail("links", "give exactly one of robot.preset (pelican) or robot.links");
  if (has_preset) {
    const std::string preset = robot.text("preset");
    if (preset != "pelican") robot.fail("preset", "unknown preset '" + preset + "'; expected: pelican");
    params = model::pelicanParams();
  } else {
    YAML::Node links = robot.child("links");
    if (!links.IsSequence() || links.size() == 0)
      robot.fail("links", "expected a non-empty list of links, each with length, com, mass, inertia");
    for (size_t i = 0; i < links.size(); ++i) {
      MapReader link(links[i], robot.keyPath("links") + "[" + std::to_string(i) + "]");
      model::LinkParams p;
      p.length = link.positive("length");
      p.com = link.number("com");
      if (p.com < 0.0) link.fail("com", "expected a number >= 0 (distance joint to centre of mass)");
      p.mass = link.positive("mass");
      p.inertia = link.positive("inertia");
      link.finish({"length", "com", "mass", "inertia"});
      params.links.push_back(p);
    }
  }
  params.gravity = robot.number("gravity", params.gravity);
  if (params.gravity < 0.0)
    robot.fail("gravity", "expected a number >= 0 [m/s^2], got " + std::to_string(params.gravity));
  robot.finish({"preset", "links", "gravity", "flexible"});
  return params;
}

std::optional<FlexibleConfig> readFlexible(MapReader robot, int n) {
  if (!robot.has("flexible")) return std::nullopt;
  MapReader f = robot.map("flexible");
  FlexibleConfig c;
  c.params.stiffness = f.vector("stiffness", n, true, true);
  c.params.rotor_inertia = f.vector("rotor_inertia", n, true, true);
  c.rate_sensor = f.boolean("rate_sensor", false);
  f.finish({"stiffness", "rotor_inertia", "rate_sensor"});
  return c;
}

model::ReferenceParams readReference(MapReader ref, const model::ChainParams& robot, double duration) {
  const int n = static_cast<int>(robot.links.size());
  model::ReferenceParams p;
  const std::string type = ref.text("type");
  if (type == "sine") {
    p.type = model::ReferenceType::kSine;
  } else if (type == "smooth_sine") {
    p.type = model::ReferenceType::kSmoothSine;
  } else if (type == "free_motion") {
    // The unforced motion of this very arm (Assumption 2), over the run and a second more.
    p.type = model::ReferenceType::kFreeMotion;
    p.initial_q = ref.vector("initial_q", n, false, false);
    p.initial_qdot =
        ref.has("initial_qdot") ? ref.vector("initial_qdot", n, false, false) : Eigen::VectorXd::Zero(n);
    p.chain = robot;
    p.horizon = duration + 1.0;
    ref.finish({"type", "initial_q", "initial_qdot"});
    return p;
  } else {
    ref.fail("type", "unknown reference type '" + type + "'; expected: sine, smooth_sine or free_motion");
  }
  p.offset = ref.vector("offset", n, true, false);
  p.amplitude = ref.vector("amplitude", n, true, false);
  p.frequency = ref.vector("frequency", n, true, false);
  if ((p.frequency.array() < 0.0).any())
    ref.fail("frequency", "expected numbers >= 0 [rad/s], got a negative one (" +
                              std::to_string(p.frequency.minCoeff()) + ")");
  p.phase = ref.has("phase") ? ref.vector("phase", n, true, false) : Eigen::VectorXd::Zero(n);
  if (p.type == model::ReferenceType::kSmoothSine) {
    p.alpha = ref.vector("alpha", n, true, true);
  } else if (ref.has("alpha")) {
    ref.fail("alpha", "only a smooth_sine reference has alpha");
  }
  ref.finish({"type", "offset", "amplitude", "frequency", "phase", "alpha"});
  return p;
}

Scenario readScenario(MapReader root) {
  Scenario s;
  s.name = root.text("name");
  s.description = root.text("description", "");
  s.duration = root.positive("duration");
  s.mode = root.text("mode", s.mode);
  if (s.mode != "lockstep" && s.mode != "inproc" && s.mode != "realtime")
    root.fail("mode", "unknown mode '" + s.mode + "'; expected: lockstep, realtime or inproc");

  s.robot = readRobot(root.map("robot"));
  const int n = s.dof();
  s.flexible = readFlexible(root.map("robot"), n);

  MapReader init = root.map("initial_state");
  s.initial_state.q = init.vector("q", n, false, false);
  s.initial_state.qdot = init.has("qdot") ? init.vector("qdot", n, false, false) : Eigen::VectorXd::Zero(n);
  if (s.flexible) {
    // Default: each spring's twist K^-1 g(q) holds the links at rest against gravity.
    s.initial_state.motor_q =
        init.has("motor_q")
            ? init.vector("motor_q", n, false, false)
            : Eigen::VectorXd(s.initial_state.q + model::PlanarChain(s.robot)
                                                      .gravity(s.initial_state.q)
                                                      .cwiseQuotient(s.flexible->params.stiffness));
    s.initial_state.motor_qdot =
        init.has("motor_qdot") ? init.vector("motor_qdot", n, false, false) : s.initial_state.qdot;
  } else if (init.has("motor_q") || init.has("motor_qdot")) {
    init.fail(init.has("motor_q") ? "motor_q" : "motor_qdot", "only an arm with robot.flexible has motors");
  }
  init.finish({"q", "qdot", "motor_q", "motor_qdot"});

  s.reference = readReference(root.map("reference"), s.controlModel(), s.duration);

  if (root.has("plant")) {
    MapReader plant = root.map("plant");
    s.plant.physics_step = plant.positive("physics_step", s.plant.physics_step);
    s.plant.publish_rate = plant.positive("publish_rate", s.plant.publish_rate);
    plant.finish({"physics_step", "publish_rate"});
    const double ratio = s.tickPeriod() / s.plant.physics_step;
    if (ratio < 1.0 - 1e-9 || std::abs(ratio - std::round(ratio)) > 1e-6 * ratio)
      plant.fail("physics_step", "the publish period 1/publish_rate = " + std::to_string(s.tickPeriod()) +
                                     " s must be a whole multiple of physics_step");
  }
  const double ticks = s.duration * s.plant.publish_rate;
  if (std::abs(ticks - std::round(ticks)) > 1e-6)
    root.fail("duration", "expected a whole number of publish periods (duration * plant.publish_rate)");

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
      }
    }
    act.finish({"order", "rate", "saturation", "initial_state"});
  }

  MapReader ctl = root.map("controller");
  s.controller.type = ctl.text("type");
  if (s.controller.type != "theorem1" && s.controller.type != "cascaded" && s.controller.type != "flexible")
    ctl.fail("type",
             "unknown controller type '" + s.controller.type + "'; expected: theorem1, cascaded or flexible");
  if (s.flexible && s.controller.type != "flexible")
    ctl.fail("type",
             "robot.flexible has elastic joints, which only the flexible controller (eq. 830) "
             "drives; expected: type flexible");
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
    s.controller.motor_rate = ctl.text("motor_rate");
    if (s.controller.motor_rate != "measured" && s.controller.motor_rate != "filtered")
      ctl.fail("motor_rate",
               "unknown choice '" + s.controller.motor_rate + "'; expected: measured or filtered");
    if (s.controller.motor_rate == "measured" && !s.flexible->rate_sensor)
      ctl.fail("motor_rate",
               "measured needs a motor rate sensor; expected robot.flexible.rate_sensor: true, "
               "or motor_rate: filtered");
    if (s.controller.motor_rate == "filtered")
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
      s.controller.stages.push_back({st.vector("kp", n, true, true), st.vector("kd", n, true, true),
                                     st.vector("a", n, true, true), st.vector("b", n, true, true)});
      st.finish({"kp", "kd", "a", "b"});
    }
  } else if (ctl.has("stages")) {
    ctl.fail("stages", "only the cascaded and flexible controllers have stages");
  }
  s.controller.gains.kp = ctl.vector("kp", n, true, true);
  s.controller.gains.kd = ctl.vector("kd", n, true, true);
  s.controller.gains.a = ctl.vector("a", n, true, true);
  s.controller.gains.b = ctl.vector("b", n, true, true);
  if (!ctl.has("initial_filter_state")) {
    s.controller.initial_filter_state = Eigen::VectorXd::Zero(n);
  } else if (ctl.child("initial_filter_state").IsScalar() &&
             ctl.child("initial_filter_state").Scalar() == "bumpless") {
    s.controller.initial_filter_state.reset();
  } else {
    s.controller.initial_filter_state = ctl.vector("initial_filter_state", n, true, false);
  }
  ctl.finish(
      {"type", "kp", "kd", "a", "b", "initial_filter_state", "stages", "motor_rate", "motor_rate_pole"});

  if (root.has("metrics")) {
    MapReader m = root.map("metrics");
    s.metrics.tolerance = m.positive("tolerance", s.metrics.tolerance);
    s.metrics.convergence_deadline = m.positive("convergence_deadline", s.metrics.convergence_deadline);
    s.metrics.xi_tolerance = m.positive("xi_tolerance", s.metrics.xi_tolerance);
    m.finish({"tolerance", "convergence_deadline", "xi_tolerance"});
  }
  if (root.has("lockstep")) {
    MapReader l = root.map("lockstep");
    s.lockstep.retransmit_timeout = l.positive("retransmit_timeout", s.lockstep.retransmit_timeout);
    s.lockstep.logger_window = l.integer("logger_window", s.lockstep.logger_window);
    if (s.lockstep.logger_window < 1) l.fail("logger_window", "expected a whole number >= 1");
    l.finish({"retransmit_timeout", "logger_window"});
  }
  if (root.has("realtime")) {
    MapReader r = root.map("realtime");
    s.realtime.max_torque_age = r.integer("max_torque_age", s.realtime.max_torque_age);
    if (s.realtime.max_torque_age < 1) r.fail("max_torque_age", "expected a whole number of periods >= 1");
    s.realtime.stale_torque = r.text("stale_torque", s.realtime.stale_torque);
    if (s.realtime.stale_torque != "zero" && s.realtime.stale_torque != "hold")
      r.fail("stale_torque", "unknown policy '" + s.realtime.stale_torque + "'; expected: zero or hold");
    s.realtime.hold_periods = r.integer("hold_periods", s.realtime.hold_periods);
    if (s.realtime.hold_periods < 0) r.fail("hold_periods", "expected a whole number >= 0");
    s.realtime.max_input_age = r.positive("max_input_age", s.realtime.max_input_age);
    s.realtime.priority = r.integer("priority", s.realtime.priority);
    if (s.realtime.priority < 0 || s.realtime.priority > 99)
      r.fail("priority", "expected a SCHED_FIFO priority from 1 to 99, or 0 for the normal scheduler");
    r.finish({"max_torque_age", "stale_torque", "hold_periods", "max_input_age", "priority"});
  }
  if (root.has("supervision")) {
    MapReader sv = root.map("supervision");
    if (sv.has("restart")) {
      const YAML::Node list = sv.child("restart");
      if (!list.IsSequence())
        sv.fail("restart", "expected a list of processes to restart when they die, e.g. [controller]");
      for (const auto& item : list) {
        const std::string name = item.IsScalar() ? item.as<std::string>() : "";
        if (name != "controller" && name != "actuator")
          sv.fail("restart",
                  "cannot restart '" + name +
                      "'; expected controller and/or actuator (the plant holds the simulated arm, the "
                      "logger the log)");
        if (!s.supervision.restarts(name)) s.supervision.restart.push_back(name);
      }
    }
    s.supervision.max_restarts = sv.integer("max_restarts", s.supervision.max_restarts);
    if (s.supervision.max_restarts < 0) sv.fail("max_restarts", "expected a whole number >= 0");
    sv.finish({"restart", "max_restarts"});
  }
  if (root.has("faults")) {
    MapReader f = root.map("faults");
    const int seed = f.integer("seed", static_cast<int>(s.faults.seed));
    if (seed < 0) f.fail("seed", "expected a whole number >= 0");
    s.faults.seed = static_cast<uint64_t>(seed);
    if (f.has("channels")) {
      MapReader channels = f.map("channels");
      const std::set<std::string> known = {"all",         "PLANT_POSITION",  "PLANT_TRUTH",
                                           "PLANT_MOTOR", "CONTROL_COMMAND", "ACTUATOR_STATE",
                                           "STATUS",      "SCENARIO"};
      std::set<std::string> names;
      for (const std::string& name : channels.keys()) {
        if (known.count(name) == 0)
          channels.fail(name,
                        "unknown channel; expected all, PLANT_POSITION, PLANT_TRUTH, PLANT_MOTOR, "
                        "CONTROL_COMMAND, ACTUATOR_STATE, STATUS or SCENARIO");
        names.insert(name);
        MapReader c = channels.map(name);
        ChannelFaults rule;
        const auto probability = [&](const char* key) {
          const double p = c.number(key, 0.0);
          if (p < 0.0 || p > 1.0) c.fail(key, "expected a probability from 0 to 1");
          return p;
        };
        rule.drop = probability("drop");
        rule.duplicate = probability("duplicate");
        rule.reorder = probability("reorder");
        rule.corrupt = probability("corrupt");
        rule.delay = c.number("delay", 0.0);
        if (rule.delay < 0.0) c.fail("delay", "expected a time >= 0 [s]");
        rule.delay_jitter = c.number("delay_jitter", 0.0);
        if (rule.delay_jitter < 0.0) c.fail("delay_jitter", "expected a time >= 0 [s]");
        c.finish({"drop", "duplicate", "reorder", "corrupt", "delay", "delay_jitter"});
        s.faults.channels[name] = rule;
      }
      channels.finish(names);
    }
    f.finish({"seed", "channels"});
  }
  root.finish({"name", "description", "duration", "mode", "robot", "initial_state", "reference", "plant",
               "actuator", "controller", "metrics", "lockstep", "realtime", "supervision", "faults"});
  return s;
}

}  // namespace

Scenario parseScenario(const std::string& yaml_text, const std::string& source,
                       const std::vector<std::string>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError("config: " + source + ": malformed YAML at line " + std::to_string(e.mark.line + 1) +
                      ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  if (root.IsNull())
    throw ConfigError(
        "config: " + source +
        ": no keys (the file is empty or only comments); expected a map of keys at the top level");
  if (!root.IsMap())
    throw ConfigError("config: " + source + ": expected a map of keys at the top level, got a " +
                      (root.IsSequence() ? "list" : "single value"));
  for (const auto& o : overrides) applyOverride(root, o);
  try {
    return readScenario(MapReader(root, ""));
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    // Prefix the source so the user knows which file (or --set) was wrong.
    throw ConfigError("config: " + source + ": " + what.substr(std::string("config: ").size()));
  }
}

Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) throw ConfigError("config: cannot read '" + path + "': expected a readable YAML file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parseScenario(buffer.str(), path, overrides);
}

namespace {
void emitVector(YAML::Emitter& out, const char* key, const Eigen::VectorXd& v) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < v.size(); ++i) out << v(i);
  out << YAML::EndSeq;
}
}  // namespace

std::string toYaml(const Scenario& s) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << s.name;
  out << YAML::Key << "description" << YAML::Value << s.description;
  out << YAML::Key << "duration" << YAML::Value << s.duration;
  out << YAML::Key << "mode" << YAML::Value << s.mode;

  out << YAML::Key << "robot" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "gravity" << YAML::Value << s.robot.gravity;
  out << YAML::Key << "links" << YAML::Value << YAML::BeginSeq;
  for (const auto& l : s.robot.links) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "length" << YAML::Value << l.length << YAML::Key
        << "com" << YAML::Value << l.com << YAML::Key << "mass" << YAML::Value << l.mass << YAML::Key
        << "inertia" << YAML::Value << l.inertia << YAML::EndMap;
  }
  out << YAML::EndSeq;
  if (s.flexible) {
    out << YAML::Key << "flexible" << YAML::Value << YAML::BeginMap;
    emitVector(out, "stiffness", s.flexible->params.stiffness);
    emitVector(out, "rotor_inertia", s.flexible->params.rotor_inertia);
    out << YAML::Key << "rate_sensor" << YAML::Value << s.flexible->rate_sensor << YAML::EndMap;
  }
  out << YAML::EndMap;

  out << YAML::Key << "initial_state" << YAML::Value << YAML::BeginMap;
  emitVector(out, "q", s.initial_state.q);
  emitVector(out, "qdot", s.initial_state.qdot);
  if (s.flexible) {
    emitVector(out, "motor_q", s.initial_state.motor_q);
    emitVector(out, "motor_qdot", s.initial_state.motor_qdot);
  }
  out << YAML::EndMap;

  out << YAML::Key << "reference" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "type" << YAML::Value << model::toString(s.reference.type);
  if (s.reference.type == model::ReferenceType::kFreeMotion) {
    emitVector(out, "initial_q", s.reference.initial_q);
    emitVector(out, "initial_qdot", s.reference.initial_qdot);
  } else {
    emitVector(out, "offset", s.reference.offset);
    emitVector(out, "amplitude", s.reference.amplitude);
    emitVector(out, "frequency", s.reference.frequency);
    emitVector(out, "phase", s.reference.phase);
  }
  if (s.reference.type == model::ReferenceType::kSmoothSine) emitVector(out, "alpha", s.reference.alpha);
  out << YAML::EndMap;

  out << YAML::Key << "plant" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "physics_step" << YAML::Value << s.plant.physics_step;
  out << YAML::Key << "publish_rate" << YAML::Value << s.plant.publish_rate;
  out << YAML::EndMap;

  out << YAML::Key << "actuator" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "order" << YAML::Value << s.actuator.order;
  out << YAML::Key << "rate" << YAML::Value << s.actuator.rate;
  if (s.actuator.saturation) emitVector(out, "saturation", *s.actuator.saturation);
  if (s.actuator.order > 0) {
    out << YAML::Key << "initial_state" << YAML::Value << YAML::BeginSeq;
    for (int i = 0; i < s.actuator.order; ++i) {
      out << YAML::Flow << YAML::BeginSeq;
      for (int j = 0; j < s.actuator.initial_state.cols(); ++j) out << s.actuator.initial_state(i, j);
      out << YAML::EndSeq;
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;

  out << YAML::Key << "controller" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "type" << YAML::Value << s.controller.type;
  if (!s.controller.motor_rate.empty())
    out << YAML::Key << "motor_rate" << YAML::Value << s.controller.motor_rate;
  if (s.controller.motor_rate_pole.size() > 0)
    emitVector(out, "motor_rate_pole", s.controller.motor_rate_pole);
  emitVector(out, "kp", s.controller.gains.kp);
  emitVector(out, "kd", s.controller.gains.kd);
  emitVector(out, "a", s.controller.gains.a);
  emitVector(out, "b", s.controller.gains.b);
  if (s.controller.initial_filter_state)
    emitVector(out, "initial_filter_state", *s.controller.initial_filter_state);
  else
    out << YAML::Key << "initial_filter_state" << YAML::Value << "bumpless";
  if (!s.controller.stages.empty()) {
    out << YAML::Key << "stages" << YAML::Value << YAML::BeginSeq;
    for (const auto& st : s.controller.stages) {
      out << YAML::BeginMap;
      emitVector(out, "kp", st.kp);
      emitVector(out, "kd", st.kd);
      emitVector(out, "a", st.a);
      emitVector(out, "b", st.b);
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;

  out << YAML::Key << "metrics" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "tolerance" << YAML::Value << s.metrics.tolerance;
  out << YAML::Key << "convergence_deadline" << YAML::Value << s.metrics.convergence_deadline;
  out << YAML::Key << "xi_tolerance" << YAML::Value << s.metrics.xi_tolerance;
  out << YAML::EndMap;

  out << YAML::Key << "lockstep" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "retransmit_timeout" << YAML::Value << s.lockstep.retransmit_timeout;
  out << YAML::Key << "logger_window" << YAML::Value << s.lockstep.logger_window;
  out << YAML::EndMap;

  out << YAML::Key << "realtime" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "max_torque_age" << YAML::Value << s.realtime.max_torque_age;
  out << YAML::Key << "stale_torque" << YAML::Value << s.realtime.stale_torque;
  out << YAML::Key << "hold_periods" << YAML::Value << s.realtime.hold_periods;
  out << YAML::Key << "max_input_age" << YAML::Value << s.realtime.max_input_age;
  out << YAML::Key << "priority" << YAML::Value << s.realtime.priority;
  out << YAML::EndMap;

  out << YAML::Key << "supervision" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "restart" << YAML::Value << YAML::Flow << s.supervision.restart;
  out << YAML::Key << "max_restarts" << YAML::Value << s.supervision.max_restarts;
  out << YAML::EndMap;

  out << YAML::Key << "faults" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "seed" << YAML::Value << s.faults.seed;
  out << YAML::Key << "channels" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, r] : s.faults.channels) {
    out << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "drop" << YAML::Value << r.drop << YAML::Key << "duplicate" << YAML::Value
        << r.duplicate;
    out << YAML::Key << "reorder" << YAML::Value << r.reorder << YAML::Key << "corrupt" << YAML::Value
        << r.corrupt;
    out << YAML::Key << "delay" << YAML::Value << r.delay << YAML::Key << "delay_jitter" << YAML::Value
        << r.delay_jitter;
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  out << YAML::EndMap;

  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace lagrange::config
