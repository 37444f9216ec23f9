#include "config/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "config/input_file.hpp"
#include "config/key_table.hpp"
#include "config/scenario_extends.hpp"
#include "config/scenario_sections.hpp"
#include "config/work_bounds.hpp"
#include "config/yaml_duplicates.hpp"
#include "config/yaml_reader.hpp"
#include "model/joint_springs.hpp"
#include "util/terminal_text.hpp"

namespace lagrange::config {

int Scenario::substepsPerTick() const {
  return static_cast<int>(std::llround(tickPeriod() / plant.physics_step));
}

int Scenario::torqueStepsPerTick() const {
  return actuator.rate > 0.0 ? static_cast<int>(std::llround(actuator.rate / plant.publish_rate)) : 1;
}

model::RobotModelPtr Scenario::robotModel() const {
  if (registered_robot) return registered_robot->model;
  if (urdf_model) return urdf_model;
  return std::make_shared<const model::PlanarChain>(robot);
}

model::RobotModelPtr Scenario::controlModel() const {
  if (flexible) return std::make_shared<const model::JointSprings>(robotModel(), flexible->params.stiffness);
  return robotModel();
}

long long Scenario::lastTick() const { return std::llround(duration * plant.publish_rate); }

namespace sections {
const Fields<Scenario>& headerFields() {
  using namespace field;
  static const Fields<Scenario> fields = {
      text("name", &Scenario::name, Presence::kRequired),
      text("description", &Scenario::description),
      positive("duration", &Scenario::duration, Presence::kRequired),
      choice("mode", &Scenario::mode, kModeNames, "mode"),
  };
  return fields;
}
}  // namespace sections

namespace {

// --set a.b.c=value: value is YAML ("[1, 2]", "0.5", "smooth_sine").
struct Assignment {
  std::string text;                // as the user gave it, "controller.kp=[1, 2]"
  std::vector<std::string> parts;  // the dotted key's parts
  YAML::Node value;
};

Assignment parseOverride(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("config: --set '" + assignment + "': expected key=value, e.g. controller.kp=50");
  const std::string key = assignment.substr(0, eq);
  if (key == "extends")
    throw ConfigError(
        "config: --set extends: a scenario's base is read before --set applies; expected extends "
        "in the scenario file itself");
  Assignment a{assignment, {}, {}};
  try {
    a.value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw ConfigError("config: --set " + key + ": the value is not valid YAML: " + e.msg);
  }
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) a.parts.push_back(part);
  return a;
}

std::string keyOf(const Assignment& a) { return a.text.substr(0, a.text.find('=')); }

// The map holding the key `a` names, created where absent. yaml-cpp nodes
// are references: assigning to a key of it edits the tree in place.
YAML::Node parentOf(YAML::Node& root, const Assignment& a) {
  std::vector<YAML::Node> chain{root};
  for (size_t i = 0; i + 1 < a.parts.size(); ++i) {
    YAML::Node next = chain.back()[a.parts[i]];
    if (!next.IsDefined() || next.IsNull()) {
      chain.back()[a.parts[i]] = YAML::Node(YAML::NodeType::Map);
      next = chain.back()[a.parts[i]];
    }
    if (!next.IsMap()) throw ConfigError("config: --set " + keyOf(a) + ": '" + a.parts[i] + "' is not a map");
    chain.push_back(next);
  }
  return chain.back();
}

// A --set that gives a section its type: SECTION.type=T, or SECTION={type: T, ...}.
bool givesType(const Assignment& a) {
  return (a.parts.size() >= 2 && a.parts.back() == "type" && a.value.IsScalar()) ||
         (a.value.IsMap() && a.value["type"].IsDefined());
}

// A section's type as the readers take it: its `type`, the simulated plant's
// when a plant section has none, "" for a section with no type.
std::string typeOf(const YAML::Node& section, const std::string& path) {
  const YAML::Node type = section["type"];
  if (type.IsDefined() && type.IsScalar()) return type.Scalar();
  return path == "plant" && !type.IsDefined() ? "simulated" : "";
}

// Applies the overrides to the scenario's tree: first those that give a
// section its type -- a type other than the section's replaces the section
// whole, as `extends` does (no key of the old type stays, the new type's
// defaults apply) -- then the others, in order, over the result; so the
// order of the options does not matter. Returns, for each section a type
// change replaced, the --set that replaced it ("controller" ->
// "controller.type=pd_plus_differenced").
std::map<std::string, std::string> applyOverrides(YAML::Node& root,
                                                  const std::vector<std::string>& overrides) {
  std::vector<Assignment> all;
  for (const std::string& o : overrides) all.push_back(parseOverride(o));
  std::map<std::string, std::string> replaced;
  for (const bool types : {true, false})
    for (const Assignment& a : all) {
      if (givesType(a) != types) continue;
      YAML::Node parent = parentOf(root, a);
      if (a.value.IsScalar() && a.parts.back() == "type" && a.parts.size() >= 2) {
        const std::string section = keyOf(a).substr(0, keyOf(a).size() - std::string(".type").size());
        const std::string old = typeOf(parent, section);
        if (!old.empty() && old != a.value.Scalar()) {
          for (const std::string& k : MapReader(parent, section).keys()) parent.remove(k);
          replaced[section] = a.text;
        }
      }
      parent[a.parts.back()] = a.value;
    }
  return replaced;
}

Scenario readScenario(MapReader root, const std::string& source, bool check_programs) {
  Scenario s;
  using namespace sections;
  readFieldsAmongOthers(root, s, headerFields());
  readRobotSection(root, s, std::filesystem::path(source).parent_path().string());
  readSensorsSection(root, s);  // before the controller, which may need a velocity sensor
  readInitialStateSection(root, s);
  readReferenceSection(root, s);
  readPlantSection(root, s, std::filesystem::path(source).parent_path().string(), check_programs);
  readActuatorSection(root, s);
  readControllerSection(root, s, std::filesystem::path(source).parent_path().string(), check_programs);
  readMetricsSection(root, s);
  readLockstepSection(root, s);
  readRealtimeSection(root, s);
  readSupervisionSection(root, s);
  readFaultsSection(root, s);
  readCompareSection(root, s);
  root.finish(keysUnder(""));
  checkWorkBounds(s);
  return s;
}

}  // namespace

namespace {

// The key path an error message starts with ("config: KEY: ..."), or "".
std::string keyOfError(const std::string& what) {
  const std::string prefix = "config: ";
  if (what.compare(0, prefix.size(), prefix) != 0) return "";
  const size_t end = what.find(": ", prefix.size());
  return end == std::string::npos ? "" : what.substr(prefix.size(), end - prefix.size());
}

// An error about a value --set gave points at the option, not at "(line 1)"
// of the one-line YAML the option's value was parsed from.
std::string namingTheOption(std::string what, const std::vector<std::string>& overrides) {
  const std::string key = keyOfError(what);
  for (auto o = overrides.rbegin(); o != overrides.rend(); ++o) {  // the last --set of a key wins
    const std::string set_key = o->substr(0, o->find('='));
    if (key != set_key && key.compare(0, set_key.size() + 1, set_key + ".") != 0) continue;
    const std::string from = " (from --set " + *o + ")";
    const size_t line = what.find(" (line ");
    const size_t close = line == std::string::npos ? line : what.find(')', line);
    if (close == std::string::npos) return what + from;
    return what.replace(line, close + 1 - line, from);
  }
  return what;
}

// In a tree merged from an extends chain, yaml-cpp keeps no line numbers: an
// error's "(line N)" would point at line 1. It names the line of the file
// that wrote the key instead, or, for a key none wrote (one missing), the files.
std::string namingTheChain(std::string what, const ScenarioTree& tree) {
  const std::vector<std::string>& chain = tree.chain;
  if (chain.size() < 2) return what;
  const size_t line = what.find(" (line ");
  const size_t close = line == std::string::npos ? line : what.find(')', line);
  std::string files;
  for (size_t i = 1; i < chain.size(); ++i) files += (i > 1 ? ", " : "") + chain[i];
  std::string where = " (in this file or one it extends: " + files + ")";
  if (const std::optional<KeyPlace> place = keyPlace(tree, keyOfError(what)))
    where =
        " (line " + std::to_string(place->line) +
        (place->file == 0 ? std::string(")") : " of " + chain[place->file] + ", which this file extends)");
  if (close == std::string::npos) return what + where;
  return what.replace(line, close + 1 - line, where);
}

// An error about a key of a section a --set's type replaced ("controller.kd:
// missing") says so: the file's keys of that section are gone.
std::string namingTheReplacement(std::string what, const std::map<std::string, std::string>& replaced) {
  const std::string key = keyOfError(what);
  for (const auto& [section, option] : replaced) {
    if (key.compare(0, section.size() + 1, section + ".") != 0) continue;
    const std::string note = " (--set " + option + " replaced the section " + section +
                             " whole, as a change of type does: the file's keys of it are dropped; expected "
                             "the new type's keys from --set too)";
    // The line is the file's section's, whose keys are gone: the note says where instead.
    const size_t line = what.find(" (line ");
    const size_t close = line == std::string::npos ? line : what.find(')', line);
    if (close == std::string::npos) return what + note;
    return what.replace(line, close + 1 - line, note);
  }
  return what;
}

Scenario readTree(ScenarioTree tree, const std::string& source, const std::vector<std::string>& overrides,
                  bool check_programs = true) {
  YAML::Node& root = tree.root;
  const std::map<std::string, std::string> replaced = applyOverrides(root, overrides);
  try {
    return readScenario(MapReader(root, ""), source, check_programs);
  } catch (const ConfigError& e) {
    std::string what = namingTheOption(e.what(), overrides);
    if (what.find("(from --set ") == std::string::npos) what = namingTheReplacement(what, replaced);
    if (what.find("(from --set ") == std::string::npos &&
        what.find("replaced the section") == std::string::npos)
      what = namingTheChain(what, tree);
    // Prefix the source so the user knows which file (or --set) was wrong.
    throw ConfigError("config: " + source + ": " + what.substr(std::string("config: ").size()));
  }
}

}  // namespace

Scenario parseScenario(const std::string& yaml_text, const std::string& source,
                       const std::vector<std::string>& overrides) {
  return readTree(parseScenarioTree(yaml_text, source), source, overrides);
}

namespace {

// Whether one of the user's --set names the key `key` or a map holding it.
bool overrideNames(const std::vector<std::string>& overrides, const std::string& key) {
  for (const std::string& o : overrides) {
    const std::string set_key = o.substr(0, o.find('='));
    if (key == set_key || key.compare(0, set_key.size() + 1, set_key + ".") == 0) return true;
  }
  return false;
}

// A recorded scenario's arm is the URDF it carries (robot.urdf.xml): the
// file it names is the run's host's, and a log of anyone's could name any
// file (`robot.urdf.file: /etc/shadow`) for its reader to open. Every log
// of `lagrange run` carries the copy (since URDF arms came); the user's own
// --set robot.urdf.file=F is read instead of it.
void useTheRecordedUrdf(ScenarioTree& tree, const std::string& source,
                        const std::vector<std::string>& overrides) {
  const YAML::Node& root = tree.root;  // const: looking creates no key
  const YAML::Node robot = root["robot"];
  if (!robot.IsDefined() || !robot.IsMap()) return;
  YAML::Node urdf = static_cast<const YAML::Node&>(robot)["urdf"];
  if (!urdf.IsDefined() || !urdf.IsMap()) return;
  if (overrideNames(overrides, "robot.urdf.file") && !overrideNames(overrides, "robot.urdf.xml")) {
    urdf.remove("xml");  // the user's file, read from the --set that names it
    return;
  }
  const YAML::Node& copy = urdf;
  if (copy["xml"].IsDefined() || overrideNames(overrides, "robot.urdf.xml")) return;
  const YAML::Node file = copy["file"];
  const std::string named =
      file.IsDefined() && file.IsScalar()
          ? " names the URDF file '" + util::terminalSafe(file.Scalar().substr(0, 200)) + "' but"
          : "";
  throw ConfigError("config: " + source + ": robot.urdf.xml: missing: the recorded scenario" + named +
                    " carries no copy of its URDF, and a reader of a log opens no file the log names; "
                    "expected a log of `lagrange run`, whose SCENARIO holds the URDF's text as "
                    "robot.urdf.xml");
}

}  // namespace

Scenario parseLoggedScenario(const std::string& yaml_text, const std::string& source,
                             const std::vector<std::string>& overrides) {
  ScenarioTree tree = parseRecordedScenarioTree(yaml_text, source);
  useTheRecordedUrdf(tree, source, overrides);
  return readTree(std::move(tree), source, overrides, false);
}

Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides) {
  return readTree(loadScenarioTree(path), path, overrides);
}

}  // namespace lagrange::config
