#pragma once
/// @file
/// SCENARIO: the resolved scenario as a message, for lcm-spy and the log.

#include "config/scenario.hpp"
#include "lagrange/scenario_t.hpp"

namespace lagrange::config {

/// The resolved scenario as YAML (config::toYaml).
lagrange::scenario_t scenarioMessage(const Scenario& s);

}  // namespace lagrange::config
