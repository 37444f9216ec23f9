// The baselines (docs/baselines.md) against their continuous laws: the
// sampled loop, the controller core as the processes run it and the arm by
// RK4 under the held torque, against RK4 of the continuous closed loop.
#include <gtest/gtest.h>

#include <cmath>

#include "controller/pd_plus_differenced.hpp"
#include "model/planar_chain.hpp"
#include "model/reference.hpp"
#include "support/rk4.hpp"

namespace lagrange::controller {
namespace {

model::Reference sine() {
  model::ReferenceParams p;
  p.type = model::ReferenceType::kSine;
  p.offset = Eigen::Vector2d(0.1, 0.2);
  p.amplitude = Eigen::Vector2d(0.5, 0.3);
  p.frequency = Eigen::Vector2d(2.0, 3.0);
  p.phase = Eigen::Vector2d::Zero();
  return model::Reference(p);
}

const Eigen::Vector2d kKp(150.0, 10.0), kKd(15.0, 1.0);

// PD+ with the true velocity (Paden and Panja): the continuous law.
Eigen::VectorXd pdPlus(const model::RobotModel& arm, const model::Reference& ref, double t,
                       const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  const model::ReferenceSample r = ref.evaluate(t, 2);
  return arm.inertia(q) * r.qdd() + arm.coriolis(q, v) * r.qd() + arm.gravity(q) -
         kKp.cwiseProduct(q - r.q()) - kKd.cwiseProduct(v - r.qd());
}

// The law as documented, at one sample, from its second call on.
TEST(PdPlusDifferenced, LawIsPdPlusWithTheBackwardDifference) {
  const model::PlanarChain arm(model::pelicanParams());
  const model::Reference ref = sine();
  PdPlusDifferenced ctl(arm, ref, kKp, kKd);
  const Eigen::Vector2d q0(0.4, -0.3), q1(0.41, -0.32);
  const Theorem1Output first = ctl.step(0.2, q0);
  // No previous sample: v = q_d'(t_0), so no damping kick.
  EXPECT_LT((first.theta - ref.evaluate(0.2, 1).qd()).norm(), 1e-15);
  const Theorem1Output second = ctl.step(0.201, q1);
  const Eigen::VectorXd v = (q1 - q0) / 0.001;
  EXPECT_LT((second.theta - v).norm(), 1e-9);
  EXPECT_LT((second.u - pdPlus(arm, ref, 0.201, q1, v)).norm(), 1e-9);
  EXPECT_EQ(second.q_error, q1 - ref.evaluate(0.201, 0).q());
  ctl.reset();
  EXPECT_LT((ctl.step(0.3, q0).theta - ref.evaluate(0.3, 1).qd()).norm(), 1e-15) << "reset forgets q_{k-1}";
  EXPECT_THROW(PdPlusDifferenced(arm, ref, Eigen::Vector2d(1, 0), kKd), std::invalid_argument);
}

// Max |q gap| over 3 s between the sampled loop at period T and RK4 of the
// continuous PD+ loop (step 1e-4 s), from the same state 0.6 rad off.
double gapToContinuous(double period) {
  const model::PlanarChain arm(model::pelicanParams());
  const model::Reference ref = sine();
  const Eigen::Vector2d q0(0.7, -0.4), v0(0.0, 0.0);
  const double h = 1e-4;
  // Continuous: x = [q; q'] under u(t, q, q').
  Eigen::VectorXd x(4);
  x << q0, v0;
  auto f = [&](double t, const Eigen::VectorXd& s) {
    Eigen::VectorXd d(4);
    d.head(2) = s.tail(2);
    d.tail(2) = arm.acceleration(s.head(2), s.tail(2), pdPlus(arm, ref, t, s.head(2), s.tail(2)));
    return d;
  };
  // Sampled: the core at t_k = k T, the torque held, the arm by RK4 at h.
  PdPlusDifferenced ctl(arm, ref, kKp, kKd);
  Eigen::VectorXd y(4);
  y << q0, v0;
  const int substeps = static_cast<int>(std::lround(period / h));
  double gap = 0.0, t = 0.0;
  for (int k = 0; k < static_cast<int>(std::lround(3.0 / period)); ++k) {
    const Eigen::VectorXd u = ctl.step(t, y.head(2)).u;
    for (int i = 0; i < substeps; ++i, t += h) {
      x = testing::rk4Step(f, t, x, h);
      y = testing::armStep(arm, y, u, h);
    }
    gap = std::max(gap, (x.head(2) - y.head(2)).cwiseAbs().maxCoeff());
  }
  return gap;
}

// The sampled loop follows the continuous one, closer with a shorter period
// (first order: the difference lags by half a period); both track.
TEST(PdPlusDifferenced, FollowsContinuousPdPlusCloserWithAShorterPeriod) {
  const double at1ms = gapToContinuous(1e-3), at_quarter = gapToContinuous(2.5e-4);
  std::printf("PD+ differenced vs continuous PD+, 3 s: max |q gap| %.3g rad at 1 ms, %.3g rad at 0.25 ms\n",
              at1ms, at_quarter);
  EXPECT_LT(at1ms, 2e-2);
  EXPECT_LT(at_quarter, 0.4 * at1ms);
}

}  // namespace
}  // namespace lagrange::controller
