#pragma once
/// @file
/// Sufficient gain condition of Theorem 4, eq. (12), with the paper's Remark 2 for
/// diagonal gains:  (kd_min / 2) (b_min / a_max) > k_c k_delta.

#include <Eigen/Dense>
#include <string>

namespace lagrange::model {

/// Verdict on one inequality "lhs > rhs".
struct ConditionReport {
  std::string name;        ///< the paper's printed number, e.g. "eq. (12)"
  std::string expression;  ///< the inequality in words
  double lhs = 0.0;
  double rhs = 0.0;
  bool holds = false;  ///< lhs > rhs
  /// lhs - rhs: positive when the condition holds, in the inequality's units.
  double margin() const { return lhs - rhs; }
};

/// A report of "lhs > rhs".
ConditionReport makeCondition(const std::string& name, const std::string& expression, double lhs, double rhs);

/// The LaTeX source's label of a condition named by its printed number ("eq. (12)" -> "11",
/// "eq. (74)" -> "lego"; docs/citing.md's table), or "" for a condition the paper does not number
/// (A Hurwitz, Q - diag(Q)/2 >= 0). The label is a secondary key: what the paper prints is the name.
std::string paperLabel(const std::string& name);

/// eq. (12) for per-joint gains kd, a, b (all positive) and the constants k_c, k_delta.
ConditionReport theorem1Condition(const Eigen::VectorXd& kd, const Eigen::VectorXd& a,
                                  const Eigen::VectorXd& b, double kc, double kdelta);

}  // namespace lagrange::model
