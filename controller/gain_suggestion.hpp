#pragma once
/// @file
/// `lagrange check-gains --suggest`: gains that satisfy the evaluated
/// conditions, by the constructive rules of the paper.
///
///   m = 0: kd from eq. (11) with 10 % margin, kp, a, b kept.
///   m >= 1, stage 0: b0 kept, a0 = 8 m b0 (so a0/(4 b0) - m = m), kd0 from
///     (lego) (= 632a for m = 1) with 10 % margin; kp0 kept. eta_1..3 are then
///     estimated for these stage-0 gains.
///   stage 1 (794): kp1 = kd1 = a1 = 1.1 (eta_2^2 + eta_3^2) + 2, b1 = 1.
///   stage i >= 2 (795): b_i = 1, kp_i = f_i [(eta_2^2 + eta_3^2) (prod_{j<i} beta_j)^2 + kp_{i-1}],
///     kd_i = sqrt(kp_i (kp_i - kp_{i-1})) ((795a) with kd_i^2, see model/proposition1.hpp),
///     a_i = f_i (eta_2^2 + eta_3^2)(b_i prod beta_j)^2.
///   f_i from 1.1, doubled until Proposition 1's matrix condition Q - diag(Q)/2 >= 0
///     holds for stages 1..i with room for the later ones: lambda_min(DQD) > 0.5 + 0.1 (m - i).
/// The numbers grow like (eta_2^2 + eta_3^2)^(2^i): they show how conservative
/// the proposition is rather than gains to run.
/// The suggestion is then checked with the same conditions a run reports.

#include <string>

#include "config/scenario.hpp"

namespace lagrange::controller {

/// The scenario with suggested gains (only the controller's gains change).
/// @throws std::range_error when the constructive gains overflow double (m = 4
/// typically does: stage 4's kp would be ~1e370).
config::Scenario suggestGains(const config::Scenario& scenario);

/// The controller section of a scenario as YAML, to paste into a config.
std::string controllerYaml(const config::Scenario& scenario);

}  // namespace lagrange::controller
