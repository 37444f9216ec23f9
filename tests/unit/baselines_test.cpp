// The baselines (docs/baselines.md) against their continuous laws: the
// sampled loop, the controller core as the processes run it and the arm by
// RK4 under the held torque, against RK4 of the continuous closed loop.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <tuple>

#include "controller/berghuis_nijmeijer.hpp"
#include "controller/nicosia_tomei.hpp"
#include "controller/pd_plus_differenced.hpp"
#include "controller/set_point.hpp"
#include "controller/velocity_feedback.hpp"
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

using Law = std::function<Eigen::VectorXd(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v)>;

// The sampled loop at period T against RK4 of the continuous loop (step
// 1e-4 s), from the same state 0.6 rad off on each joint, over 3 s: the max |q gap| and
// the sampled loop's final |q~|. `sampled` is the core at t_k = k T, given
// the exact q and q' at t_k; the torque is held, the arm stepped by RK4 at h.
struct LoopGap {
  double gap = 0.0;
  double final_error = 0.0;
};
LoopGap gapToContinuous(double period, const Law& continuous, const Law& sampled) {
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
    d.tail(2) = arm.acceleration(s.head(2), s.tail(2), continuous(t, s.head(2), s.tail(2)));
    return d;
  };
  Eigen::VectorXd y(4);
  y << q0, v0;
  const int substeps = static_cast<int>(std::lround(period / h));
  LoopGap out;
  double t = 0.0;
  for (int k = 0; k < static_cast<int>(std::lround(3.0 / period)); ++k) {
    const Eigen::VectorXd u = sampled(t, y.head(2), y.tail(2));
    for (int i = 0; i < substeps; ++i, t += h) {
      x = testing::rk4Step(f, t, x, h);
      y = testing::armStep(arm, y, u, h);
    }
    out.gap = std::max(out.gap, (x.head(2) - y.head(2)).cwiseAbs().maxCoeff());
  }
  out.final_error = (y.head(2) - ref.evaluate(t, 0).q()).norm();
  return out;
}

double differencedGap(double period) {
  const model::PlanarChain arm(model::pelicanParams());
  const model::Reference ref = sine();
  PdPlusDifferenced ctl(arm, ref, kKp, kKd);
  return gapToContinuous(
             period, [&](double t, const auto& q, const auto& v) { return pdPlus(arm, ref, t, q, v); },
             [&](double t, const auto& q, const auto&) { return ctl.step(t, q).u; })
      .gap;
}

// The sampled loop follows the continuous one, closer with a shorter period
// (first order: the difference lags by half a period); both track.
TEST(PdPlusDifferenced, FollowsContinuousPdPlusCloserWithAShorterPeriod) {
  const double at1ms = differencedGap(1e-3), at_quarter = differencedGap(2.5e-4);
  std::printf("PD+ differenced vs continuous PD+, 3 s: max |q gap| %.3g rad at 1 ms, %.3g rad at 0.25 ms\n",
              at1ms, at_quarter);
  EXPECT_LT(at1ms, 2e-2);
  EXPECT_LT(at_quarter, 0.4 * at1ms);
}

// Slotine and Li's law, written out here from the baselines table.
const Eigen::Vector2d kLambda(10.0, 10.0), kSlidingKd(20.0, 2.0);
Eigen::VectorXd slotineLi(const model::RobotModel& arm, const model::Reference& ref, double t,
                          const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  const model::ReferenceSample r = ref.evaluate(t, 2);
  const Eigen::VectorXd e = q - r.q(), qr_dot = r.qd() - kLambda.cwiseProduct(e);
  const Eigen::VectorXd qr_ddot = r.qdd() - kLambda.cwiseProduct(v - r.qd());
  return arm.inertia(q) * qr_ddot + arm.coriolis(q, v) * qr_dot + arm.gravity(q) -
         kSlidingKd.cwiseProduct(v - qr_dot);
}

// With the velocity measured, the cores are the laws at the sample (to
// round-off), and the sampled loops follow the continuous ones to first order
// in T while tracking, as their papers claim (global tracking).
TEST(VelocityBaselines, PdPlusAndSlotineLiAreTheirLawsAndFollowTheirContinuousLoops) {
  const model::PlanarChain arm(model::pelicanParams());
  const model::Reference ref = sine();
  const PdPlus pd(arm, ref, kKp, kKd);
  const SlotineLi sl(arm, ref, kLambda, kSlidingKd);
  const Eigen::Vector2d q(0.4, -0.3), v(1.5, -2.0);
  EXPECT_LT((pd.step(0.2, q, v).u - pdPlus(arm, ref, 0.2, q, v)).norm(), 1e-9);
  EXPECT_LT((sl.step(0.2, q, v).u - slotineLi(arm, ref, 0.2, q, v)).norm(), 1e-9);
  EXPECT_EQ(pd.step(0.2, q, v).theta, v);
  EXPECT_THROW(SlotineLi(arm, ref, Eigen::Vector2d(0, 1), kSlidingKd), std::invalid_argument);
  for (const auto& [name, continuous, sampled] :
       {std::tuple{"pd_plus",
                   Law([&](double t, const auto&x, const auto&y) { return pdPlus(arm, ref, t, x, y); }),
                   Law([&](double t, const auto&x, const auto&y) { return pd.step(t, x, y).u; })},
        std::tuple{"slotine_li",
                   Law([&](double t, const auto&x, const auto&y) { return slotineLi(arm, ref, t, x, y); }),
                   Law([&](double t, const auto&x, const auto&y) { return sl.step(t, x, y).u; })}}) {
    const LoopGap at1ms = gapToContinuous(1e-3, continuous, sampled);
    const LoopGap at_quarter = gapToContinuous(2.5e-4, continuous, sampled);
    std::printf(
        "%s vs its continuous loop, 3 s: max |q gap| %.3g rad at 1 ms, %.3g at 0.25 ms; final |q~| %.3g\n",
        name, at1ms.gap, at_quarter.gap, at1ms.final_error);
    EXPECT_LT(at1ms.gap, 2e-2) << name;
    EXPECT_LT(at_quarter.gap, 0.4 * at1ms.gap) << name;  // first order in T
    EXPECT_LT(at1ms.final_error, 1e-2) << name;          // from 0.85 rad off: it tracks
  }
}

model::Reference constant(const Eigen::Vector2d& q_d) {
  model::ReferenceParams p;
  p.type = model::ReferenceType::kSine;
  p.offset = q_d;
  p.amplitude = p.frequency = p.phase = Eigen::Vector2d::Zero();
  return model::Reference(p);
}

const Theorem1Gains kSetPointGains{Eigen::Vector2d(100.0, 20.0), Eigen::Vector2d(10.0, 2.0),
                                   Eigen::Vector2d(50.0, 50.0), Eigen::Vector2d(50.0, 50.0)};

TEST(SetPoint, LawIsGravityCompensatedPdOnTheDirtyDerivative) {
  const model::PlanarChain arm(model::pelicanParams());
  const Eigen::Vector2d q_d(0.5, -0.2);
  const model::Reference ref = constant(q_d);
  SetPoint ctl(arm, ref, kSetPointGains);
  const Eigen::Vector2d q0(0.9, 0.3), q1(0.905, 0.29);
  const Theorem1Output first = ctl.step(0.0, q0);
  EXPECT_LT(first.theta.norm(), 1e-15) << "bumpless start";
  EXPECT_LT((first.u - (arm.gravity(q0) - kSetPointGains.kp.cwiseProduct(q0 - q_d))).norm(), 1e-12);
  // One period later: qc advanced exactly with q0 held, theta = qc + b q1.
  const double dt = 1e-3;
  const Eigen::Array2d decay = (-kSetPointGains.a.array() * dt).exp();
  const Eigen::Vector2d qc = (decay * (-kSetPointGains.b.array() * q0.array()) -
                              kSetPointGains.b.array() * (1.0 - decay) * q0.array())
                                 .matrix();
  const Theorem1Output second = ctl.step(dt, q1);
  EXPECT_LT((second.theta - (qc + kSetPointGains.b.cwiseProduct(q1))).norm(), 1e-12);
  const Eigen::VectorXd error = q1 - q_d;
  const Eigen::VectorXd expected =
      arm.gravity(q1) - kSetPointGains.kp.cwiseProduct(error) - kSetPointGains.kd.cwiseProduct(second.theta);
  EXPECT_LT((second.u - expected).norm(), 1e-12);
}

// The sampled loop at period T against RK4 of the continuous one, x = [q, q',
// qc] with qc' = -a (qc + b q): the largest |q gap| over 5 s, and where each
// ends relative to q_d.
struct SetPointRun {
  double gap = 0.0, sampled_final = 0.0, continuous_final = 0.0;
};
SetPointRun setPointRun(double period) {
  const model::PlanarChain arm(model::pelicanParams());
  const Eigen::Vector2d q_d(0.5, -0.2), q0(-1.0, 1.2);
  const model::Reference ref = constant(q_d);
  const Theorem1Gains& g = kSetPointGains;
  auto law = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& qc) {
    return Eigen::VectorXd(arm.gravity(q) - g.kp.cwiseProduct(q - q_d) -
                           g.kd.cwiseProduct(qc + g.b.cwiseProduct(q)));
  };
  Eigen::VectorXd x(6);
  x << q0, Eigen::Vector2d::Zero(), -g.b.cwiseProduct(q0);
  auto f = [&](double, const Eigen::VectorXd& s) {
    Eigen::VectorXd d(6);
    d.head(2) = s.segment(2, 2);
    d.segment(2, 2) = arm.acceleration(s.head(2), s.segment(2, 2), law(s.head(2), s.tail(2)));
    d.tail(2) = -g.a.cwiseProduct(s.tail(2) + g.b.cwiseProduct(s.head(2)));
    return d;
  };
  SetPoint ctl(arm, ref, g);
  Eigen::VectorXd y(4);
  y << q0, Eigen::Vector2d::Zero();
  const double h = 1e-4;
  const int substeps = static_cast<int>(std::lround(period / h));
  SetPointRun run;
  double t = 0.0;
  for (int k = 0; k < static_cast<int>(std::lround(5.0 / period)); ++k) {
    const Eigen::VectorXd u = ctl.step(t, y.head(2)).u;
    for (int i = 0; i < substeps; ++i, t += h) {
      x = testing::rk4Step(f, t, x, h);
      y = testing::armStep(arm, y, u, h);
    }
    run.gap = std::max(run.gap, (x.head(2) - y.head(2)).cwiseAbs().maxCoeff());
  }
  run.sampled_final = (y.head(2) - q_d).norm();
  run.continuous_final = (x.head(2) - q_d).norm();
  return run;
}

// Regulation from 2 rad away, as Kelly's theorem says for the continuous loop,
// and the sampled loop follows it, closer with a shorter period.
TEST(SetPoint, RegulatesAndFollowsItsContinuousLoop) {
  const SetPointRun at1ms = setPointRun(1e-3), at_quarter = setPointRun(2.5e-4);
  std::printf(
      "set_point vs its continuous loop, 5 s: max |q gap| %.3g rad at 1 ms, %.3g at 0.25 ms; "
      "final |q - q_d| %.3g (continuous), %.3g (1 ms)\n",
      at1ms.gap, at_quarter.gap, at1ms.continuous_final, at1ms.sampled_final);
  EXPECT_LT(at1ms.continuous_final, 1e-4);
  EXPECT_LT(at1ms.sampled_final, 1e-4);
  EXPECT_LT(at1ms.gap, 5e-2);  // 1.5 % of the 2 rad start: the filter's half-period lag
  EXPECT_LT(at_quarter.gap, 0.4 * at1ms.gap);
}

const NicosiaTomeiGains kObserverGains{kKp, kKd, Eigen::Vector2d(2500.0, 2500.0),
                                       Eigen::Vector2d(100.0, 100.0)};

// An observer-based loop, x = [q, q', qh, zh], continuous (RK4 of `f`) and
// sampled (the core at period T, the arm by RK4 under the held torque): the
// largest |q gap| over 3 s from `offset` off the reference at rest, and the
// final tracking error of each.
struct ObserverRun {
  double gap = 0.0, sampled_final = 0.0, continuous_final = 0.0;
};
template <class Core, class Gains, class F>
ObserverRun observerRun(double period, const Gains& gains, const Eigen::Vector2d& offset, const F& f) {
  const model::PlanarChain arm(model::pelicanParams());
  const model::Reference ref = sine();
  const Eigen::Vector2d q0 = ref.evaluate(0.0, 0).q() + offset;
  Eigen::VectorXd x(8);
  x << q0, Eigen::Vector2d::Zero(), q0, Eigen::Vector2d::Zero();
  Core ctl(arm, ref, gains);
  Eigen::VectorXd y(4);
  y << q0, Eigen::Vector2d::Zero();
  const double h = 1e-4;
  const int substeps = static_cast<int>(std::lround(period / h));
  ObserverRun run;
  double t = 0.0;
  auto continuous = [&](double tau, const Eigen::VectorXd& state) { return f(arm, ref, tau, state); };
  for (int k = 0; k < static_cast<int>(std::lround(3.0 / period)); ++k) {
    const Eigen::VectorXd u = ctl.step(t, y.head(2)).u;
    for (int i = 0; i < substeps; ++i, t += h) {
      x = testing::rk4Step(continuous, t, x, h);
      y = testing::armStep(arm, y, u, h);
    }
    run.gap = std::max(run.gap, (x.head(2) - y.head(2)).cwiseAbs().maxCoeff());
  }
  const Eigen::VectorXd q_d = ref.evaluate(t, 0).q();
  run.sampled_final = (y.head(2) - q_d).norm();
  run.continuous_final = (x.head(2) - q_d).norm();
  return run;
}

// Nicosia and Tomei's continuous loop.
Eigen::VectorXd nicosiaTomeiLoop(const model::RobotModel& arm, const model::Reference& ref, double t,
                                 const Eigen::VectorXd& s) {
  const NicosiaTomeiGains& g = kObserverGains;
  const Eigen::VectorXd q = s.head(2), v = s.segment(2, 2), qh = s.segment(4, 2), zh = s.tail(2);
  const Eigen::VectorXd qh_dot = zh + g.ld.cwiseProduct(q - qh);
  const model::ReferenceSample r = ref.evaluate(t, 2);
  const Eigen::VectorXd u = arm.inertia(q) * r.qdd() + arm.coriolis(q, qh_dot) * r.qd() + arm.gravity(q) -
                            g.kp.cwiseProduct(q - r.q()) - g.kd.cwiseProduct(qh_dot - r.qd());
  Eigen::VectorXd d(8);
  d << v, arm.acceleration(q, v, u), qh_dot, arm.acceleration(q, qh_dot, u) + g.lp.cwiseProduct(q - qh);
  return d;
}

ObserverRun nicosiaTomeiRun(double period) {
  return observerRun<NicosiaTomei>(period, kObserverGains, Eigen::Vector2d(0.1, -0.1), nicosiaTomeiLoop);
}

// Local tracking, as the paper claims: from near the reference both loops
// converge, and the sampled one follows the continuous one, closer with a
// shorter period.
TEST(NicosiaTomei, TracksLocallyAndFollowsItsContinuousLoop) {
  const ObserverRun at1ms = nicosiaTomeiRun(1e-3), at_quarter = nicosiaTomeiRun(2.5e-4);
  std::printf(
      "nicosia_tomei vs its continuous loop, 3 s: max |q gap| %.3g rad at 1 ms, %.3g at 0.25 ms; "
      "final |q~| %.3g (continuous), %.3g (1 ms), %.3g (0.25 ms)\n",
      at1ms.gap, at_quarter.gap, at1ms.continuous_final, at1ms.sampled_final, at_quarter.sampled_final);
  EXPECT_LT(at1ms.continuous_final, 1e-4);
  EXPECT_LT(at1ms.sampled_final, 1e-4);
  EXPECT_LT(at_quarter.sampled_final, 0.4 * at1ms.sampled_final);
  EXPECT_LT(at1ms.gap, 2e-3);
  EXPECT_LT(at_quarter.gap, 0.4 * at1ms.gap);
}

TEST(NicosiaTomei, TheFirstCommandUsesTheStartingObserver) {
  const model::PlanarChain arm(model::pelicanParams());
  const model::Reference ref = sine();
  NicosiaTomei ctl(arm, ref, kObserverGains);
  const Eigen::Vector2d q0(0.4, -0.3);
  const Theorem1Output first = ctl.step(0.0, q0);
  // qh = q0, zh = 0: the velocity estimate is zero, the law PD+ with q' = 0.
  EXPECT_LT(first.theta.norm(), 1e-15);
  EXPECT_LT((first.u - pdPlus(arm, ref, 0.0, q0, Eigen::Vector2d::Zero())).norm(), 1e-9);
  EXPECT_THROW(ctl.step(0.0, q0), std::invalid_argument) << "time must advance";
}

const BerghuisNijmeijerGains kBnGains{kKp, kKd, Eigen::Vector2d(10.0, 10.0), Eigen::Vector2d(2500.0, 2500.0),
                                      Eigen::Vector2d(100.0, 100.0)};

// Berghuis and Nijmeijer's continuous loop.
Eigen::VectorXd berghuisNijmeijerLoop(const model::RobotModel& arm, const model::Reference& ref, double t,
                                      const Eigen::VectorXd& s) {
  const BerghuisNijmeijerGains& g = kBnGains;
  const Eigen::VectorXd q = s.head(2), v = s.segment(2, 2), qh = s.segment(4, 2), zh = s.tail(2);
  const model::ReferenceSample r = ref.evaluate(t, 2);
  const Eigen::VectorXd e = q - qh, qh_dot = zh + g.ld.cwiseProduct(e);
  const Eigen::VectorXd qr_dot = r.qd() - g.lambda.cwiseProduct(qh - r.q());
  const Eigen::VectorXd qr_ddot = r.qdd() - g.lambda.cwiseProduct(qh_dot - r.qd());
  const Eigen::VectorXd q0_dot = qh_dot - g.lambda.cwiseProduct(qh - q);
  const Eigen::VectorXd u = arm.inertia(q) * qr_ddot + arm.coriolis(q, q0_dot) * qr_dot + arm.gravity(q) -
                            g.kd.cwiseProduct(q0_dot - qr_dot) - g.kp.cwiseProduct(q - r.q());
  Eigen::VectorXd d(8);
  d << v, arm.acceleration(q, v, u), qh_dot, qr_ddot + g.lp.cwiseProduct(e);
  return d;
}

// Semiglobal tracking, as the paper claims: from 0.3 rad off, both loops
// converge, the sampled one following the continuous one to first order in T.
TEST(BerghuisNijmeijer, TracksAndFollowsItsContinuousLoop) {
  auto run = [](double period) {
    return observerRun<BerghuisNijmeijer>(period, kBnGains, Eigen::Vector2d(0.3, -0.3),
                                          berghuisNijmeijerLoop);
  };
  const ObserverRun at1ms = run(1e-3), at_quarter = run(2.5e-4);
  std::printf(
      "berghuis_nijmeijer vs its continuous loop, 3 s: max |q gap| %.3g rad at 1 ms, %.3g at 0.25 ms; "
      "final |q~| %.3g (continuous), %.3g (1 ms), %.3g (0.25 ms)\n",
      at1ms.gap, at_quarter.gap, at1ms.continuous_final, at1ms.sampled_final, at_quarter.sampled_final);
  EXPECT_LT(at1ms.continuous_final, 1e-4);
  EXPECT_LT(at1ms.sampled_final, 1e-4);
  EXPECT_LT(at1ms.gap, 5e-3);
  EXPECT_LT(at_quarter.gap, 0.4 * at1ms.gap);
}

TEST(BerghuisNijmeijer, TheFirstCommandUsesTheStartingObserver) {
  const model::PlanarChain arm(model::pelicanParams());
  const model::Reference ref = sine();
  BerghuisNijmeijer ctl(arm, ref, kBnGains);
  const Eigen::Vector2d q0(0.4, -0.3);
  const Theorem1Output first = ctl.step(0.0, q0);
  // qh = q0 and zh = 0: qh' = 0, so q0' = 0 and qr' = q_d' - Lambda (q0 - q_d).
  const model::ReferenceSample r = ref.evaluate(0.0, 2);
  const Eigen::VectorXd qr_dot = r.qd() - kBnGains.lambda.cwiseProduct(q0 - r.q());
  const Eigen::VectorXd qr_ddot = r.qdd() + kBnGains.lambda.cwiseProduct(r.qd());
  const Eigen::VectorXd expected = arm.inertia(q0) * qr_ddot + arm.gravity(q0) +
                                   kBnGains.kd.cwiseProduct(qr_dot) - kBnGains.kp.cwiseProduct(q0 - r.q());
  EXPECT_LT(first.theta.norm(), 1e-15);
  EXPECT_LT((first.u - expected).norm(), 1e-9);
}

}  // namespace
}  // namespace lagrange::controller
