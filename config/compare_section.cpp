/// @file
/// The compare section: what `lagrange compare` runs (docs/comparison.md).
/// Each controller's keys are kept as YAML text here and checked when
/// `lagrange compare` builds that controller's scenario, before any run
/// starts; `lagrange run` carries the section along and ignores it.
#include <yaml-cpp/yaml.h>

#include "config/key_table.hpp"
#include "config/scenario_sections.hpp"

namespace lagrange::config::sections {

void readCompareSection(MapReader& root, Scenario& s) {
  if (!root.has("compare")) return;
  MapReader r = root.map("compare");
  CompareConfig c;
  MapReader controllers = r.map("controllers");
  // The types are checked by lagrange compare, which knows every registered
  // one; a programme without the baselines linked reads this section too.
  for (const std::string& type : controllers.keys()) {
    const YAML::Node keys = controllers.child(type);
    if (!keys.IsNull() && !keys.IsMap())
      controllers.fail(type, "expected a map of the controller's keys (e.g. {kp: [150, 10], kd: [15, 1]})");
    if (keys.IsMap() && keys["type"])
      controllers.fail(type + ".type", "the controller's type is its key here; expected its other keys only");
    c.controllers.push_back({type, keys.IsNull() ? std::string("{}") : flowYaml(keys)});
  }
  if (c.controllers.empty()) r.fail("controllers", "expected at least one controller");
  if (r.has("sweep")) {
    MapReader sweep = r.map("sweep");
    c.sweep_key = sweep.text("key");
    const YAML::Node values = sweep.child("values");
    if (!values.IsSequence() || values.size() == 0)
      sweep.fail("values", "expected a list of at least one value for " + c.sweep_key);
    for (const YAML::Node& v : values) c.sweep_values.push_back(flowYaml(v));
    sweep.finish(keysUnder("compare.sweep"));
  }
  r.finish(keysUnder("compare"));
  s.compare = c;
}

}  // namespace lagrange::config::sections
