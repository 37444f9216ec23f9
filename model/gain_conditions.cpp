#include "model/gain_conditions.hpp"

#include <array>
#include <utility>

namespace lagrange::model {

std::string paperLabel(const std::string& name) {
  // Printed number -> \label in loria-observerless-tracking.tex, counted as docs/citing.md says.
  static const std::array<std::pair<const char*, const char*>, 11> kLabels{{{"eq. (12)", "11"},
                                                                            {"eq. (56a)", "632a"},
                                                                            {"eq. (56b)", "632b"},
                                                                            {"eq. (56c)", "632c"},
                                                                            {"eq. (74)", "lego"},
                                                                            {"eq. (75)", "786"},
                                                                            {"eq. (79a)", "794a"},
                                                                            {"eq. (79b)", "794b"},
                                                                            {"eq. (80a)", "795a"},
                                                                            {"eq. (80b)", "795b"},
                                                                            {"eq. (80c)", "795c"}}};
  for (const auto& [printed, label] : kLabels)
    if (name == printed) return label;
  return "";
}

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
  return makeCondition("eq. (12)", "(kd_min / 2) (b_min / a_max) > k_c k_delta",
                       0.5 * kd.minCoeff() * b.minCoeff() / a.maxCoeff(), kc * kdelta);
}

}  // namespace lagrange::model
