#include "model/gain_conditions.hpp"

namespace lagrange::model {

ConditionReport theorem1Condition(const Eigen::VectorXd& kd, const Eigen::VectorXd& a,
                                  const Eigen::VectorXd& b, double kc, double kdelta) {
  ConditionReport r;
  r.name = "eq. (11)";
  r.expression = "(kd_min / 2) (b_min / a_max) > k_c k_delta";
  r.lhs = 0.5 * kd.minCoeff() * b.minCoeff() / a.maxCoeff();
  r.rhs = kc * kdelta;
  r.holds = r.lhs > r.rhs;
  return r;
}

}  // namespace lagrange::model
