// The exact integration of the actuator's integrator chain (eq. 600).
#include "actuator/integrator_chain.hpp"

#include <gtest/gtest.h>

#include <random>

#include "support/rk4.hpp"

namespace lagrange::actuator {
namespace {

double factorial(int k) { return k <= 1 ? 1.0 : k * factorial(k - 1); }

class ChainOrder : public ::testing::TestWithParam<int> {};

// Under a constant u the chain's solution is a polynomial:
//   xi_i(t) = sum_{j>=i} xi_j(0) t^(j-i)/(j-i)! + u t^(m-i+1)/(m-i+1)!.
TEST_P(ChainOrder, MatchesTheClosedFormPolynomial) {
  const int m = GetParam(), n = 2;
  std::mt19937_64 rng(m);
  std::uniform_real_distribution<double> d(-2.0, 2.0);
  Eigen::MatrixXd xi0(m, n);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) xi0(i, j) = d(rng);
  const Eigen::Vector2d u(d(rng), d(rng));
  IntegratorChain chain(n, m, std::nullopt, xi0);
  const double dt = 0.01;
  for (int k = 0; k < 137; ++k) chain.advance(u, dt);
  const double t = 137 * dt;
  for (int i = 0; i < m; ++i) {
    Eigen::Vector2d expected = Eigen::Vector2d::Zero();
    for (int j = i; j < m; ++j) expected += xi0.row(j).transpose() * std::pow(t, j - i) / factorial(j - i);
    expected += u * std::pow(t, m - i) / factorial(m - i);
    EXPECT_LT((chain.state().row(i).transpose() - expected).norm(), 1e-10 * (1 + expected.norm()))
        << "xi_" << i + 1;
  }
}

class NonTrivialChainOrder : public ::testing::TestWithParam<int> {};

// Piecewise-constant u: agrees with RK4 of xi' = shift(xi) + e_m u on a fine grid.
TEST_P(NonTrivialChainOrder, MatchesRk4UnderAZeroOrderHeldInput) {
  const int m = GetParam(), n = 1;
  IntegratorChain chain(n, m, std::nullopt, Eigen::MatrixXd::Ones(m, n));
  Eigen::VectorXd x = Eigen::VectorXd::Ones(m);
  const double dt = 1e-3;
  for (int k = 0; k < 500; ++k) {
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, std::sin(0.05 * k));
    chain.advance(u, dt);
    auto f = [&](double, const Eigen::VectorXd& s) {
      Eigen::VectorXd ds(m);
      for (int i = 0; i + 1 < m; ++i) ds(i) = s(i + 1);
      ds(m - 1) = u(0);
      return ds;
    };
    for (int s = 0; s < 10; ++s) x = testing::rk4Step(f, 0.0, x, dt / 10);
  }
  for (int i = 0; i < m; ++i) EXPECT_NEAR(chain.state()(i, 0), x(i), 1e-12 * (1 + std::abs(x(i))));
}

// actuator.rate: S updates a period. Row s of the torque is the closed-form
// xi_1 at t + s T/S, and the chain ends the period where one step of T puts it.
TEST_P(ChainOrder, UpdatesTheTorqueSeveralTimesAPeriodExactly) {
  const int m = GetParam(), n = 2, steps = 8;
  Eigen::MatrixXd xi0(m, n);
  for (int i = 0; i < m; ++i) xi0.row(i) = Eigen::RowVector2d(1.0 + i, -0.5 * i);
  const Eigen::Vector2d u(3.0, -7.0);
  const double period = 0.02;
  IntegratorChain fine(n, m, std::nullopt, xi0), coarse(n, m, std::nullopt, xi0);
  const ActuatorOutput out = fine.step(u, period, steps);
  const ActuatorOutput once = coarse.step(u, period);
  ASSERT_EQ(out.tau.rows(), steps);
  EXPECT_EQ(out.tau.row(0), once.tau.row(0));
  for (int s = 0; s < steps; ++s) {
    const double t = s * period / steps;
    Eigen::Vector2d expected = m == 0 ? Eigen::Vector2d(u) : Eigen::Vector2d::Zero();
    if (m > 0) {
      for (int j = 0; j < m; ++j) expected += xi0.row(j).transpose() * std::pow(t, j) / factorial(j);
      expected += u * std::pow(t, m) / factorial(m);
    }
    EXPECT_LT((out.tau.row(s).transpose() - expected).norm(), 1e-12 * (1 + expected.norm())) << "step " << s;
  }
  if (m > 0) {
    EXPECT_LT((fine.state() - coarse.state()).norm(), 1e-12 * (1 + coarse.state().norm()));
  }
  EXPECT_THROW(fine.step(u, period, 0), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Orders, ChainOrder, ::testing::Values(0, 1, 2, 3, 4));
INSTANTIATE_TEST_SUITE_P(Orders, NonTrivialChainOrder, ::testing::Values(1, 2, 3, 4));

TEST(IntegratorChain, AppliesXi1HeldOverThePeriodAndClipsOnlyTheTorque) {
  const Eigen::MatrixXd xi0{{5.0}, {100.0}};  // xi_1 = 5 N m, rising at 100 N m/s
  IntegratorChain chain(1, 2, Eigen::VectorXd::Constant(1, 6.0), xi0);
  const ActuatorOutput first = chain.step(Eigen::VectorXd::Zero(1), 0.02);
  ASSERT_EQ(first.tau.rows(), 1);
  EXPECT_DOUBLE_EQ(first.tau(0, 0), 5.0);  // the torque at the start of the period
  EXPECT_FALSE(first.saturated(0));
  EXPECT_DOUBLE_EQ(chain.state()(0, 0), 7.0);  // 5 + 100 * 0.02: state not clipped
  const ActuatorOutput second = chain.step(Eigen::VectorXd::Zero(1), 0.02);
  EXPECT_DOUBLE_EQ(second.tau(0, 0), 6.0);  // clipped to the limit
  EXPECT_TRUE(second.saturated(0));
  // Four updates a period: 9, 9.5, 10, 10.5 N m, each clipped to 6 N m.
  const ActuatorOutput profile = chain.step(Eigen::VectorXd::Zero(1), 0.02, 4);
  EXPECT_EQ(profile.tau, Eigen::MatrixXd::Constant(4, 1, 6.0));
  EXPECT_TRUE(profile.saturated(0));
  EXPECT_DOUBLE_EQ(chain.state()(0, 0), 11.0);
}

TEST(IntegratorChain, OrderZeroPassesTheCommandThroughOrSaturatesPerJoint) {
  IntegratorChain free(2, 0, std::nullopt, Eigen::MatrixXd(0, 2));
  EXPECT_EQ(free.step(Eigen::Vector2d(500, -3), 1e-3).tau.row(0).transpose(), Eigen::Vector2d(500, -3));
  IntegratorChain limited(2, 0, Eigen::Vector2d(10, 1), Eigen::MatrixXd(0, 2));
  const auto out = limited.step(Eigen::Vector2d(500, -3), 1e-3);
  EXPECT_EQ(out.tau.row(0).transpose(), Eigen::Vector2d(10, -1));
  EXPECT_TRUE(out.saturated(0) && out.saturated(1));
  EXPECT_FALSE(limited.step(Eigen::Vector2d(5, 0.5), 1e-3).saturated.any());
  EXPECT_THROW(IntegratorChain(2, 0, Eigen::Vector2d(1, 0), Eigen::MatrixXd(0, 2)), std::invalid_argument);
}

TEST(IntegratorChain, RejectsBadInput) {
  EXPECT_THROW(IntegratorChain(2, 5, std::nullopt, Eigen::MatrixXd::Zero(5, 2)), std::invalid_argument);
  EXPECT_THROW(IntegratorChain(2, -1, std::nullopt, Eigen::MatrixXd::Zero(0, 2)), std::invalid_argument);
  EXPECT_THROW(IntegratorChain(2, 2, std::nullopt, Eigen::MatrixXd::Zero(1, 2)), std::invalid_argument);
  IntegratorChain ok(2, 1, std::nullopt, Eigen::MatrixXd::Zero(1, 2));
  EXPECT_THROW(ok.step(Eigen::Vector3d::Zero(), 1e-3), std::invalid_argument);
  EXPECT_THROW(ok.step(Eigen::Vector2d::Zero(), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange::actuator
