// Theorem 3: the Lyapunov solver and the conditions A Hurwitz, (lego), (786).
#include "model/theorem3.hpp"

#include <gtest/gtest.h>

#include "model/spectra.hpp"

namespace lagrange::model {
namespace {

TEST(Lyapunov, SolvesATransposePPlusPAEqualsMinusQ) {
  Eigen::MatrixXd a(3, 3);
  a << -2, 1, 0, 0, -3, 1, 0.5, 0, -1;
  const Eigen::MatrixXd q = Eigen::MatrixXd::Identity(3, 3);
  const Eigen::MatrixXd p = solveLyapunov(a, q);
  EXPECT_LT((a.transpose() * p + p * a + q).norm(), 1e-12);
  EXPECT_GT(lagrange::model::symmetricEigenvalues(p).minCoeff(), 0.0);  // A Hurwitz
}

std::vector<StageVectors> stages(int m, double kp, double kd, double a, double b) {
  return std::vector<StageVectors>(m, {Eigen::Vector2d::Constant(kp), Eigen::Vector2d::Constant(kd),
                                       Eigen::Vector2d::Constant(a), Eigen::Vector2d::Constant(b)});
}

TEST(Theorem3Conditions, PassAndFailEachByItsOwnInequality) {
  const Eigen::Vector2d kd0(500, 520), a0(400, 400), b0(10, 10);  // (lego): 500 * 8 > 2 + 2.0001 * 1600
  // m = 2, moderate stage gains, small eta: everything holds.
  EtaEstimate small{0.1, 0.05, 0.05};
  auto ok = theorem3Conditions(0.001, 0.1, small, kd0, a0, b0, stages(2, 3.0, 1.0, 5.0, 0.5));
  ASSERT_EQ(ok.size(), 3u);
  for (const auto& c : ok) EXPECT_TRUE(c.holds) << c.name << ": " << c.lhs << " > " << c.rhs;
  // (lego): a0 = b0 makes a0 / (4 b0) - m negative.
  auto lego =
      theorem3Conditions(0.001, 0.1, small, kd0, Eigen::Vector2d(10, 10), b0, stages(2, 3.0, 1.0, 5.0, 0.5));
  EXPECT_FALSE(lego[1].holds);
  EXPECT_EQ(lego[1].name, "eq. (74)");
  EXPECT_TRUE(lego[0].holds && lego[2].holds);
  // (786): a large eta_2 breaks it, A is unchanged.
  auto big = theorem3Conditions(0.001, 0.1, EtaEstimate{0.1, 50.0, 0.05}, kd0, a0, b0,
                                stages(2, 3.0, 1.0, 5.0, 0.5));
  EXPECT_TRUE(big[0].holds);
  EXPECT_FALSE(big[2].holds);
  EXPECT_EQ(big[2].name, "eq. (75)");
}

TEST(Theorem3A, FirstRowsAreThoseThePaperPrints) {
  // m = 2 with distinct gains: A(0,:) = [-kp1, 1, kd1, 0], A(2,:) = [-kd1, 0, -a1, 0]
  // and the diagonal of the lower-left block is -kd_i (sigma cancels B G1's).
  const std::vector<ScalarStage> s = {{3.0, 1.5, 20.0, 0.7}, {4.0, 2.0, 25.0, 0.8}};
  const Eigen::MatrixXd a = theorem3A(s);
  EXPECT_DOUBLE_EQ(a(0, 0), -3.0);
  EXPECT_DOUBLE_EQ(a(0, 1), 1.0);
  EXPECT_DOUBLE_EQ(a(0, 2), 1.5);
  EXPECT_DOUBLE_EQ(a(1, 1), -(4.0 - 3.0));  // -(kp2 - kp1)
  EXPECT_DOUBLE_EQ(a(2, 0), -1.5);
  EXPECT_DOUBLE_EQ(a(2, 2), -20.0);
  EXPECT_DOUBLE_EQ(a(3, 1), -2.0);  // -kd2
  const Eigen::VectorXd b = theorem3B(s);
  EXPECT_DOUBLE_EQ(b(0), -1.0);
  EXPECT_DOUBLE_EQ(b(1), -(3.0 + 0.7 * 1.5));  // -beta_1
  EXPECT_DOUBLE_EQ(b(2), 0.7);                 // b1
  EXPECT_DOUBLE_EQ(b(3), 0.8 * (3.0 + 0.7 * 1.5));
}

}  // namespace
}  // namespace lagrange::model
