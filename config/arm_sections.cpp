/// @file
/// The scenario's arm and its task: robot (links or preset, gravity, elastic
/// joints), initial_state, reference, plant (config/scenario_sections.hpp).

#include <cmath>
#include <filesystem>
#include <set>

#include "config/external_command.hpp"
#include "config/input_file.hpp"
#include "config/key_table.hpp"
#include "config/physics_engines.hpp"
#include "config/robot_kinds.hpp"
#include "config/scenario_sections.hpp"
#include "config/work_bounds.hpp"
#include "model/planar_chain.hpp"
#include "model/urdf_arm.hpp"

namespace lagrange::config::sections {

using namespace field;

// robot.links[i]: one link of a planar chain.
const Fields<model::LinkParams>& linkFields() {
  static const Fields<model::LinkParams> fields = {
      positive("length", &model::LinkParams::length, Presence::kRequired),
      nonNegative("com", &model::LinkParams::com, "expected a number >= 0 (distance joint to centre of mass)",
                  Presence::kRequired),
      positive("mass", &model::LinkParams::mass, Presence::kRequired),
      positive("inertia", &model::LinkParams::inertia, Presence::kRequired),
  };
  return fields;
}

// initial_state: every arm's joints, a list of n numbers each.
const Fields<InitialState>& initialStateFields() {
  static const Fields<InitialState> fields = {
      jointVector("q", &InitialState::q, VectorRule().required().listOnly()),
      jointVector("qdot", &InitialState::qdot, VectorRule().listOnly()),
  };
  return fields;
}
// initial_state: the motors of an arm with robot.flexible.
const Fields<InitialState>& motorStateFields() {
  static const Fields<InitialState> fields = {
      jointVector("motor_q", &InitialState::motor_q, VectorRule().listOnly()),
      jointVector("motor_qdot", &InitialState::motor_qdot, VectorRule().listOnly()),
  };
  return fields;
}

// robot.urdf: where the document is, or the document itself, and the chain
// in it. In the order config.resolved.yaml writes them.
const Fields<UrdfRobotConfig>& urdfFields() {
  static const Fields<UrdfRobotConfig> fields = {
      text("file", &UrdfRobotConfig::file),
      text("base_link", &UrdfRobotConfig::base_link, Presence::kRequired),
      text("tip_link", &UrdfRobotConfig::tip_link, Presence::kRequired),
      {"xml", [](MapReader& m, UrdfRobotConfig& c) { c.xml = m.text("xml", c.xml); },
       [](YAML::Emitter& out, const UrdfRobotConfig& c) {
         out << YAML::Key << "xml" << YAML::Value << YAML::DoubleQuoted << c.xml;
       }},
  };
  return fields;
}

// robot.flexible: elastic joints, their springs and rotors.
const Fields<FlexibleConfig>& flexibleFields() {
  static const Fields<FlexibleConfig> fields = {
      jointVector<FlexibleConfig>(
          "stiffness", [](auto& c) -> auto& { return c.params.stiffness; },
          VectorRule().required().positiveOnly()),
      jointVector<FlexibleConfig>(
          "rotor_inertia", [](auto& c) -> auto& { return c.params.rotor_inertia; },
          VectorRule().required().positiveOnly()),
      boolean("rate_sensor", &FlexibleConfig::rate_sensor),
  };
  return fields;
}

namespace {
// plant.engine: a name config knows (built in or registered); written only
// when not the default, so that an ODE scenario's resolved file stays as it was.
Field<PlantConfig> engineField() {
  return {"engine",
          [](MapReader& m, PlantConfig& c) {
            if (!m.has("engine")) return;
            const std::string name = m.text("engine");
            const std::vector<std::string> known = physicsEngineKeys();
            if (std::find(known.begin(), known.end(), name) == known.end()) {
              std::string list;
              for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
              m.fail("engine", "no physics engine '" + name + "' in this program; expected one of " + list);
            }
            c.engine = name;
          },
          [](YAML::Emitter& out, const PlantConfig& c) {
            if (c.engine != "ode") out << YAML::Key << "engine" << YAML::Value << c.engine;
          }};
}

// plant.mujoco_integrator: MuJoCo's own setting, refused beside another engine.
Field<PlantConfig> mujocoIntegratorField() {
  return {"mujoco_integrator",
          [](MapReader& m, PlantConfig& c) {
            if (!m.has("mujoco_integrator")) return;
            if (c.engine != "mujoco")
              m.fail("mujoco_integrator", "is MuJoCo's setting and plant.engine is " + c.engine +
                                              "; expected it left out, or plant.engine: mujoco");
            c.mujoco_integrator = m.choice("mujoco_integrator", kMujocoIntegratorNames, "integrator");
          },
          [](YAML::Emitter& out, const PlantConfig& c) {
            if (c.engine == "mujoco")
              out << YAML::Key << "mujoco_integrator" << YAML::Value
                  << util::nameOf(kMujocoIntegratorNames, c.mujoco_integrator);
          }};
}
}  // namespace

// plant: the engine, the physics step, the sample rate, a limit on the arm's
// rates, and which of a URDF's joint properties the plant applies.
const Fields<PlantConfig>& plantFields() {
  static const Fields<PlantConfig> fields = {
      engineField(),
      mujocoIntegratorField(),
      positive("physics_step", &PlantConfig::physics_step),
      positive("publish_rate", &PlantConfig::publish_rate),
      optionalPositive("max_rate", &PlantConfig::max_rate),
      boolean("urdf_dynamics", &PlantConfig::urdf_dynamics),
      boolean("joint_limits", &PlantConfig::joint_limits),
  };
  return fields;
}

namespace {
// A per-joint list (or one number for all) >= 0, sized by the arm; left out,
// none (and then not written either).
Field<Scenario> jointLosses(const std::string& key, std::optional<Eigen::VectorXd> PlantConfig::*member) {
  return {key,
          [key, member](MapReader& m, Scenario& s) {
            s.plant.*member = m.optionalVector(key, s.dof(), true, false);
            if (s.plant.*member && ((*(s.plant.*member)).array() < 0.0).any())
              m.fail(key, "expected numbers >= 0, got " + std::to_string((*(s.plant.*member)).minCoeff()));
          },
          [key, member](YAML::Emitter& out, const Scenario& s) {
            if (s.plant.*member) writeVector(out, key, *(s.plant.*member));
          }};
}
}  // namespace

// plant.model_error: relative sizes and the seed of the draws.
const Fields<model::ModelError>& modelErrorFields() {
  static const Fields<model::ModelError> fields = {
      nonNegative("mass", &model::ModelError::mass, "expected a relative size >= 0 (0.1: up to 10 %)"),
      nonNegative("inertia", &model::ModelError::inertia, "expected a relative size >= 0 (0.1: up to 10 %)"),
      nonNegative("com", &model::ModelError::com, "expected a relative size >= 0 (0.1: up to 10 %)"),
      seed("seed", &model::ModelError::seed),
  };
  return fields;
}

namespace {
// plant.payload: {mass, com}; com is a distance along the planar chain's last
// link, or a point in a URDF arm's tip_link frame.
Field<Scenario> payloadField() {
  return {"payload",
          [](MapReader& plant, Scenario& s) {
            if (!plant.has("payload")) return;
            if (s.registered_robot)
              plant.fail("payload", "a robot." + s.registered_robot->key +
                                        " arm takes no payload; expected it left out");
            MapReader m = plant.map("payload");
            model::Payload p;
            p.mass = m.number("mass");
            if (p.mass < 0.0) m.fail("mass", "expected a mass >= 0 [kg], got " + std::to_string(p.mass));
            if (s.urdf_model) {
              if (m.has("com")) p.com = m.vector("com", 3, false, false);
            } else if (m.has("com")) {
              const YAML::Node node = m.child("com");
              if (!node.IsScalar())
                m.fail("com",
                       "the planar chain's payload sits on its last link: expected one number, its "
                       "distance from the last joint [m]");
              p.com.x() = m.number("com");
            }
            m.finish(keysUnder("plant.payload"));
            s.plant.payload = p;
          },
          [](YAML::Emitter& out, const Scenario& s) {
            if (!s.plant.payload) return;
            out << YAML::Key << "payload" << YAML::Value << YAML::BeginMap;
            out << YAML::Key << "mass" << YAML::Value << s.plant.payload->mass;
            if (s.urdf_model)
              writeVector(out, "com", s.plant.payload->com);
            else
              out << YAML::Key << "com" << YAML::Value << s.plant.payload->com.x();
            out << YAML::EndMap;
          }};
}

Field<Scenario> modelErrorField() {
  return {"model_error",
          [](MapReader& plant, Scenario& s) {
            if (!plant.has("model_error")) return;
            if (s.registered_robot)
              plant.fail("model_error", "a robot." + s.registered_robot->key +
                                            " arm takes no model error; expected it left out");
            model::ModelError e;
            readFields(plant.map("model_error"), e, modelErrorFields());
            s.plant.model_error = e;
          },
          [](YAML::Emitter& out, const Scenario& s) {
            if (!s.plant.model_error) return;
            out << YAML::Key << "model_error" << YAML::Value << YAML::BeginMap;
            writeFields(out, *s.plant.model_error, modelErrorFields());
            out << YAML::EndMap;
          }};
}
}  // namespace

// plant: what is sized by the arm -- the joints' and rotors' losses per
// joint, the payload's point, the model error per link.
const Fields<Scenario>& plantArmFields() {
  static const Fields<Scenario> fields = {
      jointLosses("joint_damping", &PlantConfig::joint_damping),
      jointLosses("joint_friction", &PlantConfig::joint_friction),
      jointLosses("rotor_damping", &PlantConfig::rotor_damping),
      jointLosses("rotor_friction", &PlantConfig::rotor_friction),
      payloadField(),
      modelErrorField(),
  };
  return fields;
}

namespace {
using Reference = model::ReferenceParams;

void nonNegativeFrequencies(MapReader& m, const std::string& key, const Eigen::VectorXd& v) {
  if ((v.array() < 0.0).any())
    m.fail(key, "expected numbers >= 0 [rad/s], got a negative one (" + std::to_string(v.minCoeff()) + ")");
}

// A sine's keys, "type" first so that it is written first; alpha is
// smooth_sine's, and named as such when a plain sine has it.
Fields<Reference> sineFields(bool smooth) {
  Fields<Reference> fields = {
      choice("type", &Reference::type, model::kReferenceTypeNames, "reference type"),
      jointVector("offset", &Reference::offset, VectorRule().required()),
      jointVector("amplitude", &Reference::amplitude, VectorRule().required()),
      jointVector("frequency", &Reference::frequency,
                  VectorRule().required().checkedBy(nonNegativeFrequencies)),
      jointVector("phase", &Reference::phase),
  };
  if (smooth)
    fields.push_back(jointVector("alpha", &Reference::alpha, VectorRule().required().positiveOnly()));
  else
    fields.push_back({"alpha",
                      [](MapReader& m, Reference&) {
                        if (m.has("alpha")) m.fail("alpha", "only a smooth_sine reference has alpha");
                      },
                      [](YAML::Emitter&, const Reference&) {}});
  return fields;
}
}  // namespace

// reference: the keys of each type.
const Fields<model::ReferenceParams>& referenceFields(model::ReferenceType type) {
  static const Fields<Reference> sine = sineFields(false), smooth_sine = sineFields(true);
  // The unforced motion of the arm itself (Assumption 2), from this state.
  static const Fields<Reference> free_motion = {
      choice("type", &Reference::type, model::kReferenceTypeNames, "reference type"),
      jointVector("initial_q", &Reference::initial_q, VectorRule().required().listOnly()),
      jointVector("initial_qdot", &Reference::initial_qdot, VectorRule().listOnly()),
  };
  switch (type) {
    case model::ReferenceType::kSine:
      return sine;
    case model::ReferenceType::kSmoothSine:
      return smooth_sine;
    case model::ReferenceType::kFreeMotion:
      break;
  }
  return free_motion;
}

namespace {

// robot.urdf: the document (inline, or from a file relative to the scenario's
// folder) and the chain in it, built into the model here so that every
// problem is named before anything runs.
void readUrdf(MapReader robot, Scenario& s, const std::string& base_dir) {
  MapReader u = robot.map("urdf");
  UrdfRobotConfig c;
  readFieldsAmongOthers(u, c, urdfFields());
  // Given inline (a resolved scenario's), the document is used as it is and
  // the file not read again.
  if (!u.has("xml") && c.file.empty()) {
    u.fail("file", "missing; expected the URDF file of the arm (or its text as robot.urdf.xml)");
  } else if (!u.has("xml")) {
    const std::filesystem::path path = std::filesystem::path(c.file).is_relative()
                                           ? std::filesystem::path(base_dir) / c.file
                                           : std::filesystem::path(c.file);
    const FileText text = readRegularFile(path.string(), kMaxUrdfBytes, "a URDF file", c.file);
    if (!text.error.empty()) {
      if (!std::filesystem::exists(path))
        u.fail(
            "file",
            "cannot read '" + c.file + "'; expected a readable URDF file" +
                (std::filesystem::path(c.file).is_relative() ? ", relative to the scenario's folder" : "") +
                " (looked at '" + path.string() + "')");
      u.fail("file", text.error);
    }
    c.xml = text.text;
  }
  u.finish(keysOf(urdfFields()));
  try {
    s.urdf_model = model::UrdfArm::build(
        {c.xml, c.file.empty() ? "robot.urdf.xml" : c.file, c.base_link, c.tip_link, s.robot.gravity});
  } catch (const lagrange::Error& e) {
    robot.fail("urdf", e.what());
  }
  if (s.urdf_model->dof() > kMaxJoints)
    robot.fail("urdf", (c.file.empty() ? std::string("robot.urdf.xml") : c.file) + ": the chain from '" +
                           c.base_link + "' to '" + c.tip_link + "' has " +
                           std::to_string(s.urdf_model->dof()) + " moving joints; at most " +
                           std::to_string(kMaxJoints) + " are allowed (the gain check's cost grows as n^6)");
  s.urdf = c;
}

// The registered kind's key the section gives ("" for none).
std::string registeredKindKey(const MapReader& robot) {
  for (const std::string& key : robotKindKeys())
    if (robot.has(key)) return key;
  return "";
}

model::ChainParams readRobot(MapReader robot) {
  model::ChainParams params;
  const bool has_preset = robot.has("preset");
  const bool has_links = robot.has("links");
  const bool has_urdf = robot.has("urdf");
  int registered = 0;
  std::string registered_list;
  for (const std::string& key : robotKindKeys()) {
    registered += robot.has(key) ? 1 : 0;
    registered_list += (registered_list.empty() ? "robot." : ", robot.") + key;
  }
  if (int(has_preset) + int(has_links) + int(has_urdf) + registered != 1)
    robot.fail(
        "links",
        "give exactly one of robot.preset (pelican), robot.links or robot.urdf" +
            (registered_list.empty() ? "" : " (or a kind built into this program: " + registered_list + ")"));
  if (has_urdf || registered != 0) {
    // The arm is read by readUrdf or its kind; here only what it shares with the planar chain.
  } else if (has_preset) {
    const std::string preset = robot.text("preset");
    if (preset != "pelican") robot.fail("preset", "unknown preset '" + preset + "'; expected: pelican");
    params = model::pelicanParams();
  } else {
    YAML::Node links = robot.child("links");
    if (!links.IsSequence() || links.size() == 0)
      robot.fail("links", "expected a non-empty list of links, each with length, com, mass, inertia");
    if (links.size() > static_cast<std::size_t>(kMaxJoints))
      robot.fail("links", "a chain of " + std::to_string(links.size()) + " links; at most " +
                              std::to_string(kMaxJoints) +
                              " are allowed (the gain check's cost grows as n^6)");
    for (size_t i = 0; i < links.size(); ++i) {
      model::LinkParams p;
      readFields(MapReader(links[i], robot.keyPath("links") + "[" + std::to_string(i) + "]"), p,
                 linkFields());
      params.links.push_back(p);
    }
  }
  params.gravity = robot.number("gravity", params.gravity);
  if (params.gravity < 0.0)
    robot.fail("gravity", "expected a number >= 0 [m/s^2], got " + std::to_string(params.gravity));
  std::set<std::string> known = keysUnder("robot");
  for (const std::string& key : robotKindKeys()) known.insert(key);
  robot.finish(known);
  return params;
}

// robot.<key> of a registered kind: its settings, and its arm built at once,
// so that every problem is named before anything runs.
void readRegisteredRobot(MapReader robot, const std::string& key, Scenario& s) {
  const RobotKindSection& kind = *robotKindSection(key);
  MapReader section = robot.map(key);
  RegisteredRobot r{key, kind.read(section), nullptr};
  try {
    r.model = kind.model(r.settings, s.robot.gravity);
  } catch (const lagrange::BadInput& e) {
    robot.fail(key, e.what());
  }
  if (!r.model) throw std::logic_error("robot kind '" + key + "' built no model from its section");
  if (r.model->dof() > kMaxJoints)
    robot.fail(key, "an arm of " + std::to_string(r.model->dof()) + " joints; at most " +
                        std::to_string(kMaxJoints) + " are allowed (the gain check's cost grows as n^6)");
  s.registered_robot = std::move(r);
}

std::optional<FlexibleConfig> readFlexible(MapReader robot, int n) {
  if (!robot.has("flexible")) return std::nullopt;
  FlexibleConfig c;
  c.params.stiffness = c.params.rotor_inertia = Eigen::VectorXd::Zero(n);
  readFields(robot.map("flexible"), c, flexibleFields());
  return c;
}

model::ReferenceParams readReference(MapReader ref, model::RobotModelPtr arm, double duration) {
  const int n = arm->dof();
  model::ReferenceParams p;
  p.type = ref.choice("type", model::kReferenceTypeNames, "reference type");
  if (p.type == model::ReferenceType::kFreeMotion) {
    p.initial_q = p.initial_qdot = Eigen::VectorXd::Zero(n);
    readFields(ref, p, referenceFields(p.type));
    p.model = std::move(arm);
    p.horizon = duration + 1.0;  // the run and a second more
    return p;
  }
  p.offset = p.amplitude = p.frequency = p.phase = Eigen::VectorXd::Zero(n);
  if (p.type == model::ReferenceType::kSmoothSine) p.alpha = Eigen::VectorXd::Zero(n);
  readFields(ref, p, referenceFields(p.type));
  return p;
}

}  // namespace

// robot: a preset, a list of links or a URDF arm; gravity; and robot.flexible for elastic joints.
void readRobotSection(MapReader& root, Scenario& s, const std::string& base_dir) {
  s.robot = readRobot(root.map("robot"));
  if (root.map("robot").has("urdf")) {
    readUrdf(root.map("robot"), s, base_dir);
    s.robot.links.clear();
  }
  if (const std::string key = registeredKindKey(root.map("robot")); !key.empty())
    readRegisteredRobot(root.map("robot"), key, s);
  s.flexible = readFlexible(root.map("robot"), s.dof());
}

// initial_state: q, qdot, and for an elastic arm its motors.
void readInitialStateSection(MapReader& root, Scenario& s) {
  const int n = s.dof();
  MapReader init = root.map("initial_state");
  InitialState& state = s.initial_state;
  state.q = state.qdot = Eigen::VectorXd::Zero(n);
  readFieldsAmongOthers(init, state, initialStateFields());
  if (s.flexible) {
    // Default: each spring's twist K^-1 g(q) holds the links at rest against gravity.
    state.motor_q = state.q + s.robotModel()->gravity(state.q).cwiseQuotient(s.flexible->params.stiffness);
    state.motor_qdot = state.qdot;
    readFieldsAmongOthers(init, state, motorStateFields());
  } else if (init.has("motor_q") || init.has("motor_qdot")) {
    init.fail(init.has("motor_q") ? "motor_q" : "motor_qdot", "only an arm with robot.flexible has motors");
  }
  std::set<std::string> known = keysOf(initialStateFields());
  for (const std::string& key : keysOf(motorStateFields())) known.insert(key);
  init.finish(known);
}

// reference: a sine, a smooth sine or the arm's own free motion.
void readReferenceSection(MapReader& root, Scenario& s) {
  s.reference = readReference(root.map("reference"), s.controlModel(), s.duration);
}

// plant: physics_step and publish_rate; the run must last a whole number of periods.
namespace {
// What the plant's joint keys need of the arm: rotors for rotor_*, a URDF
// for urdf_dynamics and joint_limits, sound values in the URDF they take,
// and an initial state inside the stops.
void checkPlantJoints(MapReader& plant, const Scenario& s) {
  for (const char* key : {"rotor_damping", "rotor_friction"})
    if (plant.has(key) && !s.flexible)
      plant.fail(key, "only an arm with robot.flexible has rotors; expected it left out");
  for (const char* key : {"urdf_dynamics", "joint_limits"})
    if (plant.has(key) && plant.boolean(key, false) && !s.urdf_model)
      plant.fail(key,
                 "the arm has no URDF (robot.links or a preset); expected false, or plant.joint_damping "
                 "and plant.joint_friction for a chain's losses");
  if (!s.urdf_model) return;
  const std::vector<model::UrdfJointProperties>& joints = s.urdf_model->jointProperties();
  const std::vector<std::string> names = s.urdf_model->jointNames();
  if (s.plant.urdf_dynamics)
    for (size_t i = 0; i < joints.size(); ++i)
      if (!(joints[i].damping >= 0.0 && joints[i].friction >= 0.0 && std::isfinite(joints[i].damping) &&
            std::isfinite(joints[i].friction)))
        plant.fail("urdf_dynamics",
                   "joint '" + names[i] +
                       "' of the URDF has <dynamics damping=" + std::to_string(joints[i].damping) +
                       " friction=" + std::to_string(joints[i].friction) + ">; expected finite numbers >= 0");
  if (s.plant.joint_limits)
    for (size_t i = 0; i < joints.size(); ++i) {
      if (joints[i].lower && joints[i].upper && !(*joints[i].lower <= *joints[i].upper))
        plant.fail("joint_limits", "joint '" + names[i] +
                                       "' of the URDF has <limit lower=" + std::to_string(*joints[i].lower) +
                                       " upper=" + std::to_string(*joints[i].upper) +
                                       ">; expected lower <= upper");
      const double q = s.initial_state.q(static_cast<Eigen::Index>(i));
      if (joints[i].lower && joints[i].upper && !(q >= *joints[i].lower && q <= *joints[i].upper))
        plant.fail("joint_limits", "initial_state.q[" + std::to_string(i) + "] = " + std::to_string(q) +
                                       " is outside joint '" + names[i] +
                                       "''s <limit lower=" + std::to_string(*joints[i].lower) +
                                       " upper=" + std::to_string(*joints[i].upper) +
                                       ">; expected a start inside the stops");
    }
}
}  // namespace

namespace {
// plant.type external: a program from outside takes the plant's place; of the
// plant's keys only publish_rate (the run's clock) applies, and what a
// program cannot be told -- a rotor, sensor models -- is refused.
void readExternalPlant(MapReader& plant, Scenario& s, const std::string& base_dir, bool check_programs) {
  if (s.mode == Mode::kInproc)
    plant.fail("type",
               "an external plant runs as its own process over LCM; expected mode lockstep or realtime, got "
               "inproc");
  if (s.flexible) plant.fail("type", "an external plant has rigid joints only; this arm has robot.flexible");
  if (s.sensors)
    plant.fail("type",
               "an external plant measures with its own sensors, and the sensors section models the "
               "simulated plant's; expected no sensors section with plant.type external");
  const std::set<std::string> own = {"type", "publish_rate", "command", "working_directory"};
  for (const std::string& key : plant.keys())
    if (own.count(key) == 0 && keysUnder("plant").count(key) != 0)
      plant.fail(key,
                 "is a key of the simulated plant, and plant.type is external (the program simulates or "
                 "drives the arm itself); expected it left out");
  s.plant.publish_rate = plant.positive("publish_rate", s.plant.publish_rate);
  ExternalCommand external = readExternalCommand(plant, base_dir, "plant", check_programs);
  s.plant.command = std::move(external.command);
  s.plant.working_directory = std::move(external.working_directory);
  plant.finish(own);
}
}  // namespace

void readPlantSection(MapReader& root, Scenario& s, const std::string& base_dir, bool check_programs) {
  if (root.has("plant")) {
    MapReader plant = root.map("plant");
    s.plant.type = plant.text("type", "simulated");
    if (s.plant.type != "simulated" && s.plant.type != "external")
      plant.fail("type", "unknown plant type '" + s.plant.type + "'; expected simulated or external");
  }
  if (s.plant.external()) {
    MapReader plant = root.map("plant");
    readExternalPlant(plant, s, base_dir, check_programs);
  } else if (root.has("plant")) {
    MapReader plant = root.map("plant");
    readFieldsAmongOthers(plant, s.plant, plantFields());
    readFieldsAmongOthers(plant, s, plantArmFields());
    std::set<std::string> known = keysOf(plantFields());
    for (const std::string& key : keysOf(plantArmFields())) known.insert(key);
    known.insert("type");
    checkPlantJoints(plant, s);
    plant.finish(known);
    const double ratio = s.tickPeriod() / s.plant.physics_step;
    if (ratio < 1.0 - 1e-9 || std::abs(ratio - std::round(ratio)) > 1e-6 * ratio)
      plant.fail("physics_step", "the publish period 1/publish_rate = " + std::to_string(s.tickPeriod()) +
                                     " s must be a whole multiple of physics_step");
  }
  const double ticks = s.duration * s.plant.publish_rate;
  if (std::abs(ticks - std::round(ticks)) > 1e-6)
    root.fail("duration", "expected a whole number of publish periods (duration * plant.publish_rate)");
}

}  // namespace lagrange::config::sections
