#pragma once
/// @file
/// Theorem 6 (m >= 2 added integrators): the matrix A and vector B of the
/// cascade's error dynamics chi' = A chi + B xi_1*', chi = [xit_1..xit_m,
/// theta_1..theta_m] (eq. 787), and the gain conditions: A Hurwitz, (74),
/// and (75) for a Lyapunov pair (P, Q).
///
/// A is built from eq. (778) with the sigma_i of eq. (750d) kept (eq. 770
/// drops it): A = [[-(Kp + G1), Kd - G2], [-(Kd - S) + B G1, -A_f + B G2]],
/// Kp upper-bidiagonal (kp_i on the diagonal, -1 above), Kd, S = diag(sigma),
/// B, A_f diagonal, G1, G2, G3 of eq. (772) from eta_ik, mu_ik, beta_j of
/// (771). S cancels B G1's diagonal, giving the -kd_i the paper prints.
/// Gains are per joint: the cascade decouples across joints, so each joint
/// gets its own scalar A and B and the worst joint is reported.

#include <Eigen/Dense>
#include <vector>

#include "model/chain_conditions.hpp"
#include "model/gain_conditions.hpp"

namespace lagrange::model {

/// Scalar gains of stage i (1-based in the paper) for one joint.
struct ScalarStage {
  double kp, kd, a, b;
};

/// The Appendix's constants (771), 1-based i, j, k as in the paper:
///   beta_j = kp_j + b_j kd_j,
///   eta_ik = prod_{j=k+1}^{i-1} beta_j [kp_k^2 - kd_k^2 - kp_k kp_{k-1} sgn(k-1)],
///   mu_ik = prod_{j=k+1}^{i-1} beta_j kd_k (kp_k + a_k).
double appendixBeta(const std::vector<ScalarStage>& stages, int j);
double appendixEta(const std::vector<ScalarStage>& stages, int i, int k);
double appendixMu(const std::vector<ScalarStage>& stages, int i, int k);

/// A (2m x 2m) and B (2m) for one joint's stages 1..m.
Eigen::MatrixXd theorem3A(const std::vector<ScalarStage>& stages);
Eigen::VectorXd theorem3B(const std::vector<ScalarStage>& stages);

/// Solves A^T P + P A = -Q (Kronecker form). @throws lagrange::RuntimeFault if singular.
Eigen::MatrixXd solveLyapunov(const Eigen::MatrixXd& a, const Eigen::MatrixXd& q);

/// Per-joint stage gains: stages[i] = {kp, kd, a, b} vectors of stage i+1.
struct StageVectors {
  Eigen::VectorXd kp, kd, a, b;
};

/// Theorem 6's conditions for m = stages.size() >= 1 (worst joint each):
///   "A Hurwitz": -max Re eig(A) > 0 on the balanced A; when -(A + A^T) > 0
///     (P = I is a Lyapunov matrix) A is Hurwitz whatever the eigenvalue solver says;
///   "(74)": kd0_min (a0_min/(4 b0_max) - m) > (m+2)/2 + [k_c k_delta + (m+2)/2] (a0_max/b0_min)^2;
///   "(75)": Q - (eta_2^2 + eta_3^2) diag{|[P B]_i|^2} > 0 for one of two (P, Q):
///     P = I with Q = -(A + A^T) (Proposition 1's choice) and Q = I with P > 0 solving
///     the Lyapunov equation; the value is the smallest eigenvalue after scaling by
///     diag(Q)^-1/2 (see definiteness.hpp), the better pair per joint.
std::vector<ConditionReport> theorem3Conditions(double kc, double kdelta, const EtaEstimate& eta,
                                                const Eigen::VectorXd& kd0, const Eigen::VectorXd& a0,
                                                const Eigen::VectorXd& b0,
                                                const std::vector<StageVectors>& stages);

}  // namespace lagrange::model
