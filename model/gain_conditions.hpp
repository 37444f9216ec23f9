#pragma once
/// @file
/// Sufficient gain condition of Theorem 1, eq. (11), with Remark 1 for
/// diagonal gains:  (kd_min / 2) (b_min / a_max) > k_c k_delta.

#include <Eigen/Dense>
#include <string>

namespace lagrange::model {

/// Verdict on one inequality "lhs > rhs".
struct ConditionReport {
  std::string name;        ///< e.g. "eq. (11)"
  std::string expression;  ///< the inequality in words
  double lhs = 0.0;
  double rhs = 0.0;
  bool holds = false;  ///< lhs > rhs
  /// lhs - rhs: positive when the condition holds, in the inequality's units.
  double margin() const { return lhs - rhs; }
};

/// A report of "lhs > rhs".
ConditionReport makeCondition(const std::string& name, const std::string& expression, double lhs, double rhs);

/// eq. (11) for per-joint gains kd, a, b (all positive) and the constants k_c, k_delta.
ConditionReport theorem1Condition(const Eigen::VectorXd& kd, const Eigen::VectorXd& a,
                                  const Eigen::VectorXd& b, double kc, double kdelta);

}  // namespace lagrange::model
