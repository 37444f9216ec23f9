#pragma once
/// @file
/// Sufficient gain conditions of Theorem 5 (one added integrator, m = 1),
/// eqs. (56a)–(56c), and the constants eta_1, eta_2, eta_3 of the bound (650):
///   ||xi_1*'|| <= eta_1 sat(||q~||) + eta_2 ||q~'|| + eta_3 ||theta_0||.
///
/// With h(t, q) = D(q) qd'' + C(q, qd') qd' + g(q), differentiating eq. (48)
/// along the closed loop gives
///   xi_1*' = [dh/dq - diag(kp0 + kd0 b0)] q~' + diag(kd0 a0) theta_0 + [dh/dq qd' + dh/dt],
/// so eta_3 = max(kd0 a0) exactly, and
///   eta_2 = sup_{t,q} || dh/dq(t,q) - diag(kp0 + kd0 b0) ||,
///   eta_1 = sup_{t,q} || dh/dq qd' + dh/dt || / sat(||q - qd||),  sat(s) = min(s, 1).
/// The last bracket vanishes at q = qd only when q_d is a free motion
/// (Assumption 2); for other references eta_1 grows as the sampled radius
/// shrinks, and the estimate says so by being large.
///
/// Method (no closed form in the paper): sampled suprema. t on 400 points of
/// [0, T] with T = 2 x the longest reference period plus the smooth start's
/// settling time (at least 10 s); for each t, q at qd(t) plus radii 1e-2, 1e-1,
/// 1, 10 in 4 seeded random directions (eta_1, eta_2), and 4 seeded random q
/// on the torus (eta_2; D, C, g are 2 pi-periodic in q). dh/dq and dh/dt by
/// central differences (step 1e-6). From the 8 best samples of each, a compass
/// search over (t, q) climbs to a local maximum (eta_1 keeping |q - q_d| >=
/// 1e-2). Both estimates are then multiplied by 1.1. They are estimates, not
/// bounds, and the verdicts that use them say so.

#include <Eigen/Dense>
#include <vector>

#include "model/gain_conditions.hpp"
#include "model/reference.hpp"
#include "model/robot_model.hpp"

namespace lagrange::model {

struct EtaEstimate {
  double eta1 = 0.0, eta2 = 0.0, eta3 = 0.0;
};

/// Stage-0 gains per joint: kp0, kd0, a0, b0 (all positive).
EtaEstimate estimateEta(const RobotModel& arm, const Reference& reference, const Eigen::VectorXd& kp0,
                        const Eigen::VectorXd& kd0, const Eigen::VectorXd& a0, const Eigen::VectorXd& b0);

/// Eq. (632a-c), with diagonal gains taken conservatively: the smallest
/// gain where a larger one helps, the largest where it hurts:
///   (632a) kd0_min (a0_min / (4 b0_max) - 1) > 3/2 + (k_c k_delta + 3/2) (a0_max / b0_min)^2
///   (632b) kp1_min > (eta_2^2 + eta_3^2) / 2 + 2
///   (632c) a1_min > (b1_max^2 (eta_2^2 + eta_3^2) + 1) / 2
///
/// (632c) as printed lacks b1^2 on eta_2^2: a1 > (eta_2^2 + eta_3^2 b1^2 + 1) / 2.
/// The proof's bound (700), -[a1 - b1^2 (eta_2^2 + eta_3^2) / 2] |theta_1|^2, and
/// the alpha_3 it defines before (745) from the triangle inequality, with its
/// [1 + eta_2^2 b1^2 + eta_3^2 b1^2], both carry it; so does (795c) at i = 1.
/// This code uses the corrected form (docs/paper_in_code.md, "Choices where the paper is silent": its two
/// typos of the paper).
std::vector<ConditionReport> theorem2Conditions(double kc, double kdelta, const EtaEstimate& eta,
                                                const Eigen::VectorXd& kd0, const Eigen::VectorXd& a0,
                                                const Eigen::VectorXd& b0, const Eigen::VectorXd& kp1,
                                                const Eigen::VectorXd& a1, const Eigen::VectorXd& b1);

}  // namespace lagrange::model
