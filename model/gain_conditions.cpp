#include "model/gain_conditions.hpp"

namespace lagrange::model {

ConditionReport makeCondition(const std::string& name, const std::string& expression, double lhs,
                              double rhs) {
  ConditionReport r;
  r.name = name;
  r.expression = expression;
  r.lhs = lhs;
  r.rhs = rhs;
  r.holds = lhs > rhs;
  return r;
}

ConditionReport theorem1Condition(const Eigen::VectorXd& kd, const Eigen::VectorXd& a,
                                  const Eigen::VectorXd& b, double kc, double kdelta) {
  return makeCondition("eq. (11)", "(kd_min / 2) (b_min / a_max) > k_c k_delta",
                       0.5 * kd.minCoeff() * b.minCoeff() / a.maxCoeff(), kc * kdelta);
}

}  // namespace lagrange::model
