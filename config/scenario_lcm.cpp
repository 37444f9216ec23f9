#include "config/scenario_lcm.hpp"

namespace lagrange::config {

lagrange::scenario_t scenarioMessage(const Scenario& s) {
  lagrange::scenario_t m;
  m.name = s.name;
  m.yaml = toYaml(s);
  return m;
}

}  // namespace lagrange::config
