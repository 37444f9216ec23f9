// References: analytic derivatives against finite differences; the bounds
// k_delta and k_c against brute-force sampling they must dominate.
#include <gtest/gtest.h>

#include <random>

#include "model/bounds.hpp"
#include "model/reference.hpp"

namespace lagrange::model {
namespace {

ReferenceParams pelicanReference(ReferenceType type) {
  ReferenceParams p;
  p.type = type;
  p.offset = Eigen::Vector2d(M_PI / 4, M_PI / 3);
  p.amplitude = Eigen::Vector2d(M_PI / 9, M_PI / 6);
  p.frequency = Eigen::Vector2d(4.0, 3.0);
  p.phase = Eigen::Vector2d(0.0, 0.3);
  p.alpha = Eigen::Vector2d(2.0, 1.8);
  return p;
}

class ReferenceDerivatives : public ::testing::TestWithParam<ReferenceType> {};

TEST_P(ReferenceDerivatives, MatchFiniteDifferences) {
  const Reference ref(pelicanReference(GetParam()));
  const double h = 1e-5;
  for (double t : {0.0, 0.05, 0.3, 0.77, 1.2, 2.5, 6.0}) {
    const double tc = std::max(t, h);  // central differences need t - h >= 0
    for (int joint = 0; joint < 2; ++joint) {
      for (int order = 1; order <= 4; ++order) {
        const double fd =
            (ref.jointDerivative(joint, order - 1, tc + h) - ref.jointDerivative(joint, order - 1, tc - h)) /
            (2 * h);
        EXPECT_NEAR(ref.jointDerivative(joint, order, tc), fd, 1e-5 * (1 + std::abs(fd)))
            << "t=" << tc << " joint=" << joint << " order=" << order;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Types, ReferenceDerivatives,
                         ::testing::Values(ReferenceType::kSine, ReferenceType::kSmoothSine));

TEST(Reference, SmoothSineStartsAtRest) {
  const Reference ref(pelicanReference(ReferenceType::kSmoothSine));
  const ReferenceSample s = ref.evaluate(0.0);
  for (int k = 0; k <= 2; ++k) EXPECT_LT(s.derivative[k].norm(), 1e-15) << "order " << k;
}

TEST(Bounds, KdeltaDominatesADenseSampling) {
  for (auto type : {ReferenceType::kSine, ReferenceType::kSmoothSine}) {
    const Reference ref(pelicanReference(type));
    const double kdelta = referenceBound(ref);
    double sampled = 0.0;
    for (double t = 0.0; t < 30.0; t += 1e-4) {
      const ReferenceSample s = ref.evaluate(t);
      sampled = std::max({sampled, s.q().norm(), s.qd().norm(), s.qdd().norm()});
    }
    EXPECT_GE(kdelta, sampled);
    EXPECT_LT(kdelta, 1.5 * sampled) << "bound uselessly loose";
  }
}

TEST(Bounds, KcDominatesRandomCoriolisRatios) {
  ChainParams p;
  p.links = {{0.3, 0.15, 3.0, 0.02}, {0.3, 0.1, 2.0, 0.015}, {0.2, 0.1, 1.0, 0.004}};
  for (const ChainParams& params : {pelicanParams(), p}) {
    const PlanarChain chain(params);
    const double kc = coriolisBound(chain);
    std::mt19937_64 rng(3);
    std::normal_distribution<double> nd;
    double sampled = 0.0;
    for (int s = 0; s < 20000; ++s) {
      Eigen::VectorXd q(chain.dof()), y(chain.dof());
      for (int i = 0; i < chain.dof(); ++i) {
        q(i) = 10 * nd(rng);
        y(i) = nd(rng);
      }
      const double ratio = chain.coriolis(q, y).jacobiSvd().singularValues()(0) / y.norm();
      sampled = std::max(sampled, ratio);
    }
    EXPECT_GE(kc, sampled);
    EXPECT_LT(kc, 2.0 * sampled) << "bound uselessly loose";
  }
}

TEST(Bounds, PelicanKcIsSqrt3TimesM2L1Lc2) {
  // For the Pelican, [C_1 C_2] = h sin(q2) [[0, -1, -1, -1], [1, 0, 0, 0]],
  // whose spectral norm is sqrt(3) h |sin q2|, h = m2 l1 lc2.
  const double h = 2.0458 * 0.26 * 0.0229;
  EXPECT_NEAR(coriolisBound(PlanarChain(pelicanParams())), 1.05 * std::sqrt(3.0) * h, 1e-9);
}

}  // namespace
}  // namespace lagrange::model

namespace lagrange::model {
namespace {

TEST(FreeMotionReference, SolvesTheUnforcedDynamicsAndConservesEnergy) {
  ReferenceParams p;
  p.type = ReferenceType::kFreeMotion;
  p.initial_q = Eigen::Vector2d(0.5, 0.3);
  p.initial_qdot = Eigen::Vector2d(0.0, 1.0);
  p.chain = pelicanParams();
  p.horizon = 3.0;
  const Reference ref(p);
  const PlanarChain chain(pelicanParams());
  const double e0 = chain.kineticEnergy(p.initial_q, p.initial_qdot) + chain.potentialEnergy(p.initial_q);
  for (double t : {0.0, 0.00013, 0.5, 1.23456, 2.9}) {
    const ReferenceSample s = ref.evaluate(t, 2);
    // D q'' + C q' + g = 0 (Assumption 2).
    EXPECT_LT((chain.inertia(s.q()) * s.qdd() + chain.coriolis(s.q(), s.qd()) * s.qd() + chain.gravity(s.q()))
                  .norm(),
              1e-9);
    EXPECT_NEAR(chain.kineticEnergy(s.q(), s.qd()) + chain.potentialEnergy(s.q()), e0,
                1e-9 * std::abs(e0) + 1e-12);
    // q' is the derivative of q, also between integration nodes.
    const double h = 1e-6;
    if (t > h) {
      const Eigen::VectorXd fd = (ref.evaluate(t + h, 0).q() - ref.evaluate(t - h, 0).q()) / (2 * h);
      EXPECT_LT((fd - s.qd()).norm(), 1e-6);
    }
  }
  EXPECT_THROW(ref.evaluate(10.0, 0), std::invalid_argument);  // beyond the integrated horizon
  EXPECT_THROW(ref.evaluate(1.0, 3), std::invalid_argument);   // derivatives up to the 2nd only
  // k_delta dominates what the trajectory reaches.
  double reached = 0.0;
  for (double t = 0.0; t < 3.0; t += 1e-3) {
    const ReferenceSample s = ref.evaluate(t, 2);
    reached = std::max({reached, s.q().norm(), s.qd().norm(), s.qdd().norm()});
  }
  EXPECT_GE(referenceBound(ref), reached);
}

}  // namespace
}  // namespace lagrange::model
