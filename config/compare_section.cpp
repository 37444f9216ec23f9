/// @file
/// The compare section: what `lagrange compare` runs (docs/comparison.md).
/// Each controller's keys are kept as YAML text here and checked when
/// `lagrange compare` builds that controller's scenario, before any run
/// starts; `lagrange run` carries the section along and ignores it.
#include <yaml-cpp/yaml.h>

#include "config/scenario_sections.hpp"

namespace lagrange::config::sections {

namespace {
// compare.controllers: TYPE -> its keys, kept as YAML flow text. The types
// are checked by lagrange compare, which knows every registered one; a
// programme without the baselines linked reads this section too.
void readControllers(MapReader& r, CompareConfig& c) {
  MapReader controllers = r.map("controllers");
  for (const std::string& type : controllers.keys()) {
    const YAML::Node keys = controllers.child(type);
    if (!keys.IsNull() && !keys.IsMap())
      controllers.fail(type, "expected a map of the controller's keys (e.g. {kp: [150, 10], kd: [15, 1]})");
    // A `type` key makes the name a row label: several external programs
    // (type external, each its command), or one type tuned twice.
    if (keys.IsMap() && keys["type"] && (!keys["type"].IsScalar() || keys["type"].Scalar().empty()))
      controllers.fail(type + ".type", "expected a controller type, e.g. type: external");
    c.controllers.push_back({type, keys.IsNull() ? std::string("{}") : flowYaml(keys)});
  }
  if (c.controllers.empty()) r.fail("controllers", "expected at least one controller");
}
void writeControllers(YAML::Emitter& out, const CompareConfig& c) {
  out << YAML::Key << "controllers" << YAML::Value << YAML::BeginMap;
  for (const auto& [type, keys] : c.controllers)
    out << YAML::Key << type << YAML::Value << YAML::Flow << YAML::Load(keys);
  out << YAML::EndMap;
}

// compare.sweep.values: each value as YAML text.
void readSweepValues(MapReader& sweep, CompareConfig& c) {
  const YAML::Node values = sweep.child("values");
  if (!values.IsSequence() || values.size() == 0)
    sweep.fail("values", "expected a list of at least one value for " + c.sweep_key);
  for (const YAML::Node& v : values) c.sweep_values.push_back(flowYaml(v));
}
void writeSweepValues(YAML::Emitter& out, const CompareConfig& c) {
  out << YAML::Key << "values" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const std::string& v : c.sweep_values) out << YAML::Load(v);
  out << YAML::EndSeq;
}
}  // namespace

const Fields<CompareConfig>& compareSweepFields() {
  static const Fields<CompareConfig> fields = {
      field::text("key", &CompareConfig::sweep_key, Presence::kRequired),
      {"values", readSweepValues, writeSweepValues},
  };
  return fields;
}

const Fields<CompareConfig>& compareFields() {
  static const Fields<CompareConfig> fields = {
      {"controllers", readControllers, writeControllers},
      {"sweep",
       [](MapReader& r, CompareConfig& c) {
         if (r.has("sweep")) readFields(r.map("sweep"), c, compareSweepFields());
       },
       [](YAML::Emitter& out, const CompareConfig& c) {
         if (c.sweep_key.empty()) return;
         out << YAML::Key << "sweep" << YAML::Value << YAML::BeginMap;
         writeFields(out, c, compareSweepFields());
         out << YAML::EndMap;
       }},
  };
  return fields;
}

void readCompareSection(MapReader& root, Scenario& s) {
  if (!root.has("compare")) return;
  CompareConfig c;
  readFields(root.map("compare"), c, compareFields());
  s.compare = c;
}

}  // namespace lagrange::config::sections
