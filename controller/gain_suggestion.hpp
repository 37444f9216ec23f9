#pragma once
/// @file
/// `lagrange check-gains --suggest`: gains that satisfy the evaluated
/// conditions, by the constructive rules of the paper.
///
///   m = 0: kd from eq. (12) with 10 % margin, kp, a, b kept.
///   m >= 1, stage 0: b0 kept, a0 = 8 m b0 (so a0/(4 b0) - m = m), kd0 from
///     (74) (= 632a for m = 1) with 10 % margin; kp0 kept. eta_1..3 are then
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

#include <optional>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "controller/sampled_data.hpp"

namespace lagrange::controller {

/// The scenario with suggested gains (only the controller's gains change).
/// @throws std::range_error when the constructive gains overflow double (m = 4
/// typically does: stage 4's kp would be ~1e370).
config::Scenario suggestGains(const config::Scenario& scenario);

/// What `check-gains --suggest` found at the configured rate
/// (plant.publish_rate): gains its cheap checks pass, or none and why.
///
/// Theorem 4 (controller.type theorem1): eq. (12) asks kd_min b_min / a_max
/// > 2 k_c k_delta. Only the products kd_i b_i, the filter poles a_i and kp
/// shape the loop, so the candidates keep eq. (12) with 10 % margin -- kd
/// raised to kd_need = 1.1 * 2 k_c k_delta a_max / b_min where below it --
/// and scale the filter (a and b together by 1, 1/2, ..., 1/256, then 2, 4,
/// 8: a slower filter lowers the loop's high-frequency gain kd b / D(q), which
/// is what the rate cannot follow on a light joint), then kp by 1, 1/2, 1/4.
/// Each is linearised at the configured rate (controller::checkSampledData,
/// the cheap check); the first ADEQUATE one closest to the configured gains
/// is suggested, else the first SLOW one. Before all that the reference's own
/// torque (the inverse dynamics along q_d) is held against
/// actuator.saturation: no gains track a reference the limits cannot drive.
/// When none passes, `binding` says which condition binds: the torque limits,
/// or eq. (12) against the rate -- then what rate would let an eq. (12)
/// candidate be adequate, and up to which k_delta eq. (12) holds with gains
/// the rate allows (kd lowered from kd_need by halves until the loop is not
/// unstable). The cascaded controller keeps the constructive rules below,
/// linearised the same way; other controllers get no suggestion. The
/// simulated check (wiring/sampled_simulation.hpp) is the caller's, once, on
/// the suggestion (check-gains does it).
struct GainSearch {
  std::optional<config::Scenario> suggested;  ///< none: no candidate passed
  SampledDataCheck linearised;                ///< the suggestion's linearised check (or the last candidate's)
  std::vector<std::string> tried;             ///< one line per candidate linearised: gains and verdict
  std::string binding;                        ///< when none: which condition binds, with the numbers
  std::optional<double>
      sufficient_rate;  ///< when none: a rate at which an eq. (12) candidate is adequate [Hz]
  std::optional<double> kdelta_allowed;  ///< when none: k_delta below which eq. (12) holds with stable gains
  double kdelta = 0.0;                   ///< the reference's k_delta
};

/// The search above. @throws std::range_error as suggestGains does (chains).
GainSearch searchGains(const config::Scenario& scenario);

/// The controller section of a scenario as YAML, to paste into a config.
std::string controllerYaml(const config::Scenario& scenario);

}  // namespace lagrange::controller
