#include "model/proposition1.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "model/definiteness.hpp"

namespace lagrange::model {

Eigen::MatrixXd proposition1Q(const std::vector<ScalarStage>& s) {
  const int m = static_cast<int>(s.size());
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  for (int i = 1; i <= m; ++i) {
    q(i - 1, i - 1) = 2.0 * (s[i - 1].kp - (i > 1 ? s[i - 2].kp : 0.0));
    q(m + i - 1, m + i - 1) = 2.0 * s[i - 1].a;
    if (i < m) q(i - 1, i) = q(i, i - 1) = -1.0;
    for (int k = 1; k < i; ++k) {
      const double mu = appendixMu(s, i, k);
      q(i - 1, m + k - 1) = q(m + k - 1, i - 1) = -mu;
      q(m + i - 1, m + k - 1) = q(m + k - 1, m + i - 1) = s[i - 1].b * mu;
    }
  }
  return q;
}

namespace {
// Tracks the worst case of "lhs > rhs" over joints and stages by the ratio lhs / rhs.
struct Worst {
  double lhs = 0.0, rhs = 0.0;
  bool seen = false;
  void offer(double l, double r) {
    if (!seen || l * rhs < lhs * r) lhs = l, rhs = r, seen = true;  // l / r < lhs / rhs, r > 0
  }
};

double relativeMismatch(double x, double y) { return std::abs(x - y) / std::max(std::abs(x), std::abs(y)); }
}  // namespace

std::vector<ConditionReport> proposition1Conditions(const EtaEstimate& eta,
                                                    const std::vector<StageVectors>& stages) {
  const int m = static_cast<int>(stages.size());
  const double e = eta.eta2 * eta.eta2 + eta.eta3 * eta.eta3;
  double mismatch_794a = 0.0, mismatch_795a = 0.0, matrix = 1e300;
  Worst w794b, w795b, w795c;
  for (Eigen::Index j = 0; j < stages.front().kp.size(); ++j) {
    std::vector<ScalarStage> s;
    for (const auto& st : stages) s.push_back({st.kp(j), st.kd(j), st.a(j), st.b(j)});
    mismatch_794a = std::max(mismatch_794a, relativeMismatch(s[0].kp, s[0].kd));
    w794b.offer(std::min(s[0].a / (s[0].b * s[0].b), s[0].kp), e);
    double beta_product = 1.0;  // prod_{j=0}^{i-1} beta_j, beta_0 = 1
    for (int i = 2; i <= m; ++i) {
      const ScalarStage& now = s[i - 1];
      const double previous_kp = s[i - 2].kp;
      beta_product *= appendixBeta(s, i - 1);
      mismatch_795a =
          std::max(mismatch_795a, relativeMismatch(now.kd * now.kd, now.kp * (now.kp - previous_kp)));
      w795b.offer(now.kp, e * beta_product * beta_product + previous_kp);
      w795c.offer(now.a, e * std::pow(now.b * beta_product, 2));
    }
    const Eigen::MatrixXd q = proposition1Q(s);
    matrix = std::min(matrix, scaledMinEigenvalue(q, q));
  }
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%g", kEqualityTolerance);
  const std::string tol = tolerance;
  return {
      makeCondition("eq. (79a)", "kp1 = kd1: " + tol + " > |kp1 - kd1| / max(kp1, kd1) (worst joint)",
                    kEqualityTolerance, mismatch_794a),
      makeCondition("eq. (79b)", "min{a1 / b1^2, kp1} > eta_2^2 + eta_3^2 (corrected reading; worst joint)",
                    w794b.lhs, w794b.rhs),
      makeCondition("eq. (80a)",
                    "kd_i^2 = kp_i (kp_i - kp_{i-1}) (the printed 4 kd_i under the root read as 4 kd_i^2): " +
                        tol + " > relative mismatch (worst joint and stage)",
                    kEqualityTolerance, mismatch_795a),
      makeCondition("eq. (80b)",
                    "kp_i > (eta_2^2 + eta_3^2) (prod_{j<i} beta_j)^2 + kp_{i-1} (worst joint and stage)",
                    w795b.lhs, w795b.rhs),
      makeCondition("eq. (80c)",
                    "a_i > (eta_2^2 + eta_3^2) (b_i prod_{j<i} beta_j)^2 (worst joint and stage)", w795c.lhs,
                    w795c.rhs),
      // Q - diag(Q)/2 >= 0  <=>  lambda_min(D Q D) >= 1/2, D = diag(Q)^-1/2 (a congruence).
      makeCondition("Q - diag(Q)/2 >= 0 (Proposition 1)",
                    "lambda_min(D Q D) >= 1/2, D = diag(Q)^-1/2, Q as printed (worst joint)", matrix, 0.5),
  };
}

}  // namespace lagrange::model
