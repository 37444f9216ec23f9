#pragma once
/// @file
/// The gain check of a scenario: k_c and k_delta from the configured robot
/// and reference, then eq. (12) (Theorem 4) and, for the cascaded controller
/// with m = 1, eqs. (56a)–(56c) (Theorem 5), with m >= 2 Theorem 6's (A Hurwitz,
/// (74), (75)), using the estimated eta_1..eta_3. For m >= 2 Proposition 1's
/// constructive conditions are reported too; they are sufficient for
/// Theorem 6's, which alone decide holds().

#include <optional>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "controller/sampled_data.hpp"
#include "model/chain_conditions.hpp"
#include "model/gain_conditions.hpp"

namespace lagrange::controller {

struct GainReport {
  double kc = 0.0;        ///< model::coriolisBound when kc_proven, else kc_found
  bool kc_proven = true;  ///< the model has a closed form of C (RobotModel::coriolisTerms)
  double kc_found = 0.0;  ///< the largest ||C(q, y)|| / ||y|| found: how tight kc is
  double kdelta = 0.0;    ///< exact for a sine reference, else a sampled estimate
  bool kdelta_exact = true;
  model::ConditionReport condition;                 ///< eq. (12), on the stage-0 gains
  std::vector<model::ConditionReport> chain;        ///< eqs. (56a)–(56c) for m = 1, Theorem 6's for m >= 2
  std::vector<model::ConditionReport> proposition;  ///< m >= 2: (632a-c), (794), (795), Q - diag Q / 2 >= 0
  std::optional<model::EtaEstimate> eta;            ///< cascaded controller
  std::vector<std::string> warnings;                ///< hypotheses of the theorems that do not hold
  /// Whether the sampled implementation at the configured rate is adequate:
  /// the continuous-time conditions above say nothing about it.
  SampledDataCheck sampled;
  /// The sampled loop simulated against a fine-rate one, when the caller ran
  /// it (wiring::simulateSampledData: check-gains does; lagrange run does not
  /// simulate before a run, so its gains.json carries none). Printed first:
  /// it is the verdict.
  std::optional<SampledSimulation> simulated;
  /// Set when no stability condition is known for the controller (one
  /// registered outside the paper): why nothing was checked. The fields
  /// above are then empty and holds() is false.
  std::optional<std::string> unchecked;

  /// Every evaluated continuous-time condition holds (the theorems' verdict;
  /// the sampled-data check is apart).
  bool holds() const;
  /// The smallest margin among the evaluated conditions.
  double margin() const;
  /// The condition a reader should be told of: when holds(), the one with the
  /// smallest margin (margin()'s); when not, the violated one with the smallest
  /// margin -- never a holding condition beside a violated verdict.
  const model::ConditionReport& binding() const;
  /// Every condition of Proposition 1 holds (false when it does not apply).
  bool propositionHolds() const;
};

/// The gain check of the scenario's controller (its registry entry's; see
/// controller/registry.cpp).
/// @param sampled_data also run the sampled-data check (tens of ms to a second;
///        the processes skip it at start and leave `sampled` empty).
GainReport checkGains(const config::Scenario& scenario, bool sampled_data = true);

/// The check of the paper's controllers (theorem1, cascaded, flexible).
GainReport checkPaperGains(const config::Scenario& scenario, bool sampled_data);

/// Lines a person reads: each condition's verdict, both sides and margin.
std::string describe(const GainReport& report);

}  // namespace lagrange::controller
