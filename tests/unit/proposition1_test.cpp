// Proposition 1 and the scaled sign tests it needs: the printed Q against
// -(A + A^T), the reading of (795a), and each condition passing and failing.
#include "model/proposition1.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "model/definiteness.hpp"

namespace lagrange::model {
namespace {

// Stage gains with kp1 = kd1 (794a) and kd_i from (795a): with `square`, the
// reading this code takes (kd_i^2 = kp_i (kp_i - kp_{i-1})), else the printed one.
std::vector<ScalarStage> constructive(int m, bool square) {
  std::vector<ScalarStage> s;
  double kp_prev = 0.0;
  for (int i = 1; i <= m; ++i) {
    const double kp = 3.0 + 4.5 * i * i, a = 7.0 + i, b = 0.5 + 0.25 * i;
    const double kd = i == 1 ? kp : square ? std::sqrt(kp * (kp - kp_prev)) : kp * (kp - kp_prev);
    s.push_back({kp, kd, a, b});
    kp_prev = kp;
  }
  return s;
}

TEST(Proposition1, PrintedQIsMinusATransposeMinusAWhenKdSquaredSolves795a) {
  for (int m = 2; m <= 4; ++m) {
    const auto s = constructive(m, true);
    for (int i = 2; i <= m; ++i)
      for (int k = 1; k < i; ++k)
        EXPECT_NEAR(appendixEta(s, i, k), 0.0, 1e-9 * appendixMu(s, i, k)) << i << k;
    const Eigen::MatrixXd a = theorem3A(s);
    const Eigen::MatrixXd q = proposition1Q(s);
    EXPECT_LT((q + a + a.transpose()).norm(), 1e-12 * q.norm()) << "m = " << m;
  }
}

TEST(Proposition1, PrintedReadingOf795aLeavesEtaNonzero) {
  // kd_i = kp_i (kp_i - kp_{i-1}), as (795a) prints it: eta_ik != 0, so P = I
  // does not give the proposition's Q, and the proof's first step fails.
  // (eta_i1 vanishes by (794a) alone; the reading matters from k = 2, i.e. m >= 3.)
  const auto s3 = constructive(3, false);
  EXPECT_GT(std::abs(appendixEta(s3, 3, 2)), 1.0);
  const Eigen::MatrixXd a = theorem3A(s3);
  EXPECT_GT((proposition1Q(s3) + a + a.transpose()).norm(), 1.0);
}

std::vector<StageVectors> vectors(const std::vector<ScalarStage>& s) {
  std::vector<StageVectors> out;
  for (const auto& x : s)
    out.push_back({Eigen::Vector2d::Constant(x.kp), Eigen::Vector2d::Constant(x.kd),
                   Eigen::Vector2d::Constant(x.a), Eigen::Vector2d::Constant(x.b)});
  return out;
}

ConditionReport named(const std::vector<ConditionReport>& all, const std::string& name) {
  for (const auto& c : all)
    if (c.name == name) return c;
  ADD_FAILURE() << "no condition " << name;
  return {};
}

// m = 2 gains that meet every condition for eta_2^2 + eta_3^2 = 0.02: stage 1
// small, stage 2 large enough that mu_21 = 18 is small next to Q's diagonal.
std::vector<ScalarStage> passing() {
  return {{3.0, 3.0, 3.0, 1.0}, {1000.0, std::sqrt(1000.0 * 997.0), 1000.0, 1.0}};
}
const EtaEstimate kSmallEta{0.0, 0.1, 0.1};

TEST(Proposition1Conditions, AllHoldForAPassingSet) {
  const auto r = proposition1Conditions(kSmallEta, vectors(passing()));
  ASSERT_EQ(r.size(), 6u);
  for (const auto& c : r) EXPECT_TRUE(c.holds) << c.name << ": " << c.lhs << " > " << c.rhs;
}

TEST(Proposition1Conditions, EachFailsByItsOwnInequality) {
  auto s = passing();
  s[0].kd = 3.1;
  EXPECT_FALSE(named(proposition1Conditions(kSmallEta, vectors(s)), "eq. (79a)").holds);

  const auto big_eta = proposition1Conditions(EtaEstimate{0.0, 2.0, 0.0}, vectors(passing()));  // e = 4 > 3
  EXPECT_FALSE(named(big_eta, "eq. (79b)").holds);
  EXPECT_TRUE(named(big_eta, "eq. (80b)").holds);

  s = passing();
  s[1].kd = 1000.0 * 997.0;  // the printed reading of (795a)
  EXPECT_FALSE(named(proposition1Conditions(kSmallEta, vectors(s)), "eq. (80a)").holds);

  s = passing();  // e = 1: (795b) needs kp2 > 36 + 3, (795c) with b2 = 0.5 needs a2 > 9
  s[1] = {30.0, std::sqrt(30.0 * 27.0), 1000.0, 0.5};
  const auto r795b = proposition1Conditions(EtaEstimate{0.0, 1.0, 0.0}, vectors(s));
  EXPECT_FALSE(named(r795b, "eq. (80b)").holds);
  EXPECT_TRUE(named(r795b, "eq. (80c)").holds);
  EXPECT_TRUE(named(r795b, "eq. (79b)").holds);

  s = passing();
  s[1].a = 0.5;  // below e beta_1^2 = 0.02 * 36
  EXPECT_FALSE(named(proposition1Conditions(kSmallEta, vectors(s)), "eq. (80c)").holds);

  s = passing();
  s[1].a = 10.0;  // (795c) still holds, but mu_21 now dominates a_2 in Q
  const auto matrix = proposition1Conditions(kSmallEta, vectors(s));
  EXPECT_TRUE(named(matrix, "eq. (80c)").holds);
  EXPECT_FALSE(named(matrix, "Q - diag(Q)/2 >= 0 (Proposition 1)").holds);
}

// (794b) as printed, min{a1, kp1} > eta_2^2 + eta_3^2, lacks b1^2 on a1 (compare
// (795c) at i = 1). With b1 = 2 and e = 4, a1 = 10 passes the printed form
// (10 > 4) and fails the corrected one (10 / 4 = 2.5 < 4).
TEST(Proposition1Conditions, Eq794bDividesA1ByB1Squared) {
  auto s = passing();
  s[0] = {10.0, 10.0, 10.0, 2.0};
  const EtaEstimate eta{0.0, 2.0, 0.0};
  const auto wide = named(proposition1Conditions(eta, vectors(s)), "eq. (79b)");
  EXPECT_FALSE(wide.holds);
  EXPECT_DOUBLE_EQ(wide.lhs, 2.5);
  s[0].b = 1.0;  // both readings agree
  const auto unit = named(proposition1Conditions(eta, vectors(s)), "eq. (79b)");
  EXPECT_TRUE(unit.holds);
  EXPECT_DOUBLE_EQ(unit.lhs, 10.0);
}

TEST(Definiteness, ScaledEigenvalueKeepsTheSignAcrossSixtyDecades) {
  // M = D C D, D = diag(1, 1e30): M is positive definite iff C is. Unscaled,
  // lambda_min(M) = det / lambda_max ~ 0.1 is below M's rounding error (~1e44).
  for (const double c : {0.9, 1.1}) {
    Eigen::Matrix2d core;
    core << 1.0, c, c, 1.0;
    const Eigen::Matrix2d d = Eigen::Vector2d(1.0, 1e30).asDiagonal();
    const Eigen::MatrixXd m = d * core * d;
    EXPECT_NEAR(scaledMinEigenvalue(m, m), 1.0 - c, 1e-12);
  }
}

TEST(Definiteness, BalancedHurwitzMarginOfABadlyScaledMatrix) {
  // A = T B T^-1 with T = diag(1e-25, 1e25) has B's eigenvalues -2.5 +- i sqrt(3.75).
  Eigen::Matrix2d b;
  b << -1.0, 3.0, -2.0, -4.0;
  const Eigen::Matrix2d t = Eigen::Vector2d(1e-25, 1e25).asDiagonal();
  const Eigen::MatrixXd a = t * b * t.inverse();
  EXPECT_NEAR(hurwitzMargin(a), 2.5, 1e-9);
  EXPECT_NEAR(hurwitzMargin(-a), -2.5, 1e-9);
}

}  // namespace
}  // namespace lagrange::model
