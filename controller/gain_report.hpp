#pragma once
/// @file
/// The Theorem 1 gain check for a scenario: k_c and k_delta from the
/// configured robot and reference, then eq. (11).

#include <string>

#include "config/scenario.hpp"
#include "model/gain_conditions.hpp"

namespace lagrange::controller {

struct GainReport {
  double kc = 0.0;
  double kdelta = 0.0;
  model::ConditionReport condition;
};

GainReport checkGains(const config::Scenario& scenario);

/// One line a person reads: verdict, both sides and the margin.
std::string describe(const GainReport& report);

}  // namespace lagrange::controller
