#pragma once
/// @file
/// Proposition 1: constructive sufficient conditions for Theorem 6 (m >= 2).
/// Besides (632) and (74), which are reported elsewhere, it asks for
///   (794a) kp_1 = kd_1,
///   (794b) min{a_1 / b_1^2, kp_1} > eta_2^2 + eta_3^2,
///   (795a) kd_i^2 = kp_i (kp_i - kp_{i-1}), i in [2, m],
///   (795b) kp_i > (eta_2^2 + eta_3^2) (prod_{j=0}^{i-1} beta_j)^2 + kp_{i-1},
///   (795c) a_i > (eta_2^2 + eta_3^2) (b_i prod_{j=0}^{i-1} beta_j)^2,   beta_0 = 1,
///   Q - 1/2 diag{Q} >= 0 for the matrix Q the proposition prints.
///
/// (795a) as printed, kp_i = [kp_{i-1} + sqrt(kp_{i-1}^2 + 4 kd_i)] / 2, means
/// kd_i = kp_i (kp_i - kp_{i-1}); but the proof needs it to zero the bracket of
/// eta_ik (771), kp_k^2 - kd_k^2 - kp_k kp_{k-1}, which takes kd_k^2 there. The
/// Appendix's eta_ik is confirmed against a numerical derivative (tests), so the
/// typo is in (795a): this code uses sqrt(kp_{i-1}^2 + 4 kd_i^2). With it and
/// (794a) every eta_ik vanishes and the printed Q equals -(A + A^T), i.e. P = I
/// in Theorem 6 (tested for m = 2..4).
///
/// (794b) as printed, min{a_1, kp_1} > eta_2^2 + eta_3^2, lacks b_1^2 on a_1:
/// (795c) at i = 1 (beta_0 = 1) reads a_1 > (eta_2^2 + eta_3^2) b_1^2, and the
/// proof's bound (800)-(820) treats stage 1 like the others. This code uses
/// the corrected form; with b_1 = 1 both agree.
///
/// Gains are per joint; each inequality reports its worst joint and stage (the
/// smallest lhs / rhs), each equality its largest relative mismatch.

#include <Eigen/Dense>
#include <vector>

#include "model/chain_conditions.hpp"
#include "model/gain_conditions.hpp"
#include "model/theorem3.hpp"

namespace lagrange::model {

/// Relative mismatch below which (794a) and (795a) count as equalities.
inline constexpr double kEqualityTolerance = 1e-9;

/// The matrix Q printed in Proposition 1 for one joint (2m x 2m, order
/// [xit_1..xit_m, theta_1..theta_m]).
Eigen::MatrixXd proposition1Q(const std::vector<ScalarStage>& stages);

/// (794a), (794b), (795a), (795b), (795c) and "Q - 1/2 diag Q >= 0", in that order.
std::vector<ConditionReport> proposition1Conditions(const EtaEstimate& eta,
                                                    const std::vector<StageVectors>& stages);

}  // namespace lagrange::model
