// The dirty-derivative filter's exact discretisation and the Theorem 1 law.
#include <gtest/gtest.h>

#include "controller/dirty_derivative.hpp"
#include "controller/theorem1.hpp"
#include "model/gain_conditions.hpp"
#include "support/rk4.hpp"

namespace lagrange::controller {
namespace {

TEST(DirtyDerivative, OneStepEqualsTheContinuousSolutionUnderHeldInput) {
  const Eigen::Vector2d a(200.0, 35.0), b(150.0, 35.0), qc0(3.0, -1.0), x(0.4, -2.0);
  DirtyDerivativeFilter f(a, b, qc0);
  const double dt = 1e-3;  // a dt = 0.2 and 0.035
  f.advance(x, dt);
  // qc' = -a (qc + b x) with x constant, integrated by RK4 with 10^4 sub-steps.
  Eigen::VectorXd qc = qc0;
  auto rhs = [&](double, const Eigen::VectorXd& s) {
    return Eigen::VectorXd(-(a.array() * (s.array() + b.array() * x.array())).matrix());
  };
  for (int i = 0; i < 10000; ++i) qc = testing::rk4Step(rhs, 0.0, qc, dt / 10000);
  EXPECT_LT((f.state() - qc).norm(), 1e-12 * (1 + qc.norm()));
  // Closed form, written out.
  for (int i = 0; i < 2; ++i) {
    const double e = std::exp(-a(i) * dt);
    EXPECT_DOUBLE_EQ(f.state()(i), e * qc0(i) - b(i) * (1 - e) * x(i));
  }
}

TEST(DirtyDerivative, ExactForLargeStepsWhereEulerFails) {
  // a dt = 2: forward Euler would flip the sign of the state every step.
  DirtyDerivativeFilter f(Eigen::VectorXd::Constant(1, 200.0), Eigen::VectorXd::Constant(1, 1.0),
                          Eigen::VectorXd::Constant(1, 1.0));
  for (int k = 0; k < 5; ++k) f.advance(Eigen::VectorXd::Zero(1), 0.01);
  EXPECT_NEAR(f.state()(0), std::exp(-200.0 * 0.05), 1e-15);
  EXPECT_GT(f.state()(0), 0.0);
}

TEST(DirtyDerivative, OutputApproximatesBTimesTheDerivativeOverA) {
  // theta = b s / (s + a) x: for a slow ramp x = r t, theta -> (b / a) r.
  const double a = 100.0, b = 100.0, r = 0.7, dt = 1e-3;
  DirtyDerivativeFilter f(Eigen::VectorXd::Constant(1, a), Eigen::VectorXd::Constant(1, b),
                          Eigen::VectorXd::Zero(1));
  double theta = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, r * k * dt);
    theta = f.output(x)(0);
    f.advance(x, dt);
  }
  // ZOH sampling adds half a sample of lag: theta = (b/a) r (1 + O(a dt)).
  EXPECT_NEAR(theta, b / a * r, 0.06 * r);
}

struct Fixture {
  model::PlanarChain chain{model::pelicanParams()};
  model::Reference reference{[] {
    model::ReferenceParams p;
    p.type = model::ReferenceType::kSine;
    p.offset = Eigen::Vector2d(0.1, 0.2);
    p.amplitude = Eigen::Vector2d(0.5, 0.3);
    p.frequency = Eigen::Vector2d(2.0, 3.0);
    p.phase = Eigen::Vector2d::Zero();
    return p;
  }()};
  Theorem1Gains gains{Eigen::Vector2d(100, 20), Eigen::Vector2d(10, 2), Eigen::Vector2d(50, 60),
                      Eigen::Vector2d(40, 70)};
};

TEST(Theorem1, LawIsEquation90c) {
  Fixture fx;
  Theorem1Controller ctl(fx.chain, fx.reference, fx.gains, Eigen::Vector2d(0.3, -0.2));
  const double t = 0.37;
  const Eigen::Vector2d q(0.9, -1.1);
  const Theorem1Output out = ctl.step(t, q);
  const model::ReferenceSample r = fx.reference.evaluate(t);
  const Eigen::Vector2d qt = q - r.q();
  const Eigen::Vector2d theta = Eigen::Vector2d(0.3, -0.2) + fx.gains.b.cwiseProduct(qt);
  const Eigen::Vector2d expected = -fx.gains.kp.cwiseProduct(qt) - fx.gains.kd.cwiseProduct(theta) +
                                   fx.chain.inertia(q) * r.qdd() + fx.chain.coriolis(q, r.qd()) * r.qd() +
                                   fx.chain.gravity(q);
  EXPECT_LT((out.u - expected).norm(), 1e-12);
  EXPECT_LT((out.theta - theta).norm(), 1e-12);
}

TEST(Theorem1, FilterAdvancesByElapsedTimeWithPreviousErrorHeld) {
  Fixture fx;
  Theorem1Controller ctl(fx.chain, fx.reference, fx.gains, Eigen::Vector2d::Zero());
  const Eigen::Vector2d q0(0.9, -1.1);
  const Theorem1Output first = ctl.step(0.0, q0);
  ctl.step(0.003, Eigen::Vector2d(0.5, 0.5));  // 3 ms later: a missed sample in between
  DirtyDerivativeFilter reference_filter(fx.gains.a, fx.gains.b, Eigen::Vector2d::Zero());
  reference_filter.advance(first.q_error, 0.003);
  EXPECT_LT((ctl.filterState() - reference_filter.state()).norm(), 1e-12);
  EXPECT_THROW(ctl.step(0.003, q0), std::invalid_argument);  // time must increase
}

TEST(Theorem1, BumplessStartGivesZeroThetaAtTheFirstStep) {
  Fixture fx;
  Theorem1Controller ctl(fx.chain, fx.reference, fx.gains, std::nullopt);
  const Theorem1Output out = ctl.step(0.0, Eigen::Vector2d(2.0, -1.5));
  EXPECT_LT(out.theta.norm(), 1e-12);
  EXPECT_LT((out.filter_state + fx.gains.b.cwiseProduct(out.q_error)).norm(), 1e-12);
}

TEST(Theorem1, RejectsNonPositiveGainsAndWrongSizes) {
  Fixture fx;
  Theorem1Gains bad = fx.gains;
  bad.kd(1) = 0.0;
  EXPECT_THROW(Theorem1Controller(fx.chain, fx.reference, bad, std::nullopt), std::invalid_argument);
  bad = fx.gains;
  bad.a = Eigen::Vector3d(1, 2, 3);
  EXPECT_THROW(Theorem1Controller(fx.chain, fx.reference, bad, std::nullopt), std::invalid_argument);
  Theorem1Controller ok(fx.chain, fx.reference, fx.gains, std::nullopt);
  EXPECT_THROW(ok.step(0.0, Eigen::Vector3d::Zero()), std::invalid_argument);
}

TEST(GainCondition, UsesSmallestKdAndBAndLargestA) {
  // Remark 1: (kd_min / 2)(b_min / a_max) > k_c k_delta.
  const auto r = model::theorem1Condition(Eigen::Vector2d(4, 10), Eigen::Vector2d(50, 100),
                                          Eigen::Vector2d(100, 80), 0.5, 1.0);
  EXPECT_DOUBLE_EQ(r.lhs, 0.5 * 4 * 80 / 100);
  EXPECT_DOUBLE_EQ(r.rhs, 0.5);
  EXPECT_TRUE(r.holds);
  const auto v = model::theorem1Condition(Eigen::Vector2d(4, 10), Eigen::Vector2d(50, 100),
                                          Eigen::Vector2d(100, 80), 0.5, 4.0);
  EXPECT_FALSE(v.holds);
  EXPECT_LT(v.margin(), 0.0);
}

}  // namespace
}  // namespace lagrange::controller
