// References: analytic derivatives against finite differences; the bounds
// k_delta and k_c against brute-force sampling they must dominate.
#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "model/bounds.hpp"
#include "model/planar_chain.hpp"
#include "model/reference.hpp"
#include "model/spectra.hpp"

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
    const double kc = coriolisBound(chain).value();
    std::mt19937_64 rng(3);
    std::normal_distribution<double> nd;
    double sampled = 0.0;
    for (int s = 0; s < 20000; ++s) {
      Eigen::VectorXd q(chain.dof()), y(chain.dof());
      for (int i = 0; i < chain.dof(); ++i) {
        q(i) = 10 * nd(rng);
        y(i) = nd(rng);
      }
      const double ratio = lagrange::model::largestSingularValue(chain.coriolis(q, y)) / y.norm();
      sampled = std::max(sampled, ratio);
    }
    EXPECT_GE(kc, sampled);
    EXPECT_LT(kc, 2.0 * sampled) << "bound uselessly loose";
  }
}

TEST(Bounds, PelicanKcIsSqrt3TimesM2L1Lc2) {
  // For the Pelican, [C_1 C_2] = h sin(q2) [[0, -1, -1, -1], [1, 0, 0, 0]],
  // whose spectral norm is sqrt(3) h |sin q2|, h = m2 l1 lc2: one link pair,
  // so the proven bound is the supremum itself, and the search finds it.
  const double h = 2.0458 * 0.26 * 0.0229;
  const PlanarChain pelican(pelicanParams());
  EXPECT_NEAR(coriolisBound(pelican).value(), std::sqrt(3.0) * h, 1e-12);
  EXPECT_NEAR(coriolisLargestFound(pelican), std::sqrt(3.0) * h, 1e-12);
}

// An 8-link chain whose tip link weighs 10 kg.
ChainParams heavyTipChain() {
  ChainParams p;
  for (int i = 0; i < 8; ++i) p.links.push_back({0.25, 0.12, 1.0, 0.006});
  p.links.back() = {0.25, 0.2, 10.0, 0.08};
  return p;
}

TEST(Bounds, TheClosedFormOfCIsTheChristoffelSymbols) {
  for (const ChainParams& params : {pelicanParams(), heavyTipChain()}) {
    const PlanarChain chain(params);
    const int n = chain.dof();
    const std::vector<CoriolisTerm> terms = chain.coriolisTerms().value();
    EXPECT_EQ(terms.size(), static_cast<size_t>(n * (n - 1) / 2));
    std::mt19937_64 rng(5);
    std::normal_distribution<double> nd;
    for (int s = 0; s < 50; ++s) {
      Eigen::VectorXd q(n);
      for (int i = 0; i < n; ++i) q(i) = 3 * nd(rng);
      Eigen::VectorXd phi(n);
      std::partial_sum(q.data(), q.data() + n, phi.data());
      const std::vector<Eigen::MatrixXd> ck = chain.coriolisPerVelocity(q);
      for (int k = 0; k < n; ++k) {
        Eigen::MatrixXd closed = Eigen::MatrixXd::Zero(n, n);
        for (const CoriolisTerm& t : terms) closed += std::sin(phi(t.a) - phi(t.b)) * t.per_velocity[k];
        EXPECT_LT((closed - ck[k]).norm(), 1e-12 * (1.0 + ck[k].norm())) << "k = " << k;
      }
    }
  }
}

// k_c used to be 1.05 x the largest G(q) = ||[C_1(q) ... C_n(q)]|| on 20000
// random relative angles. For the heavy-tipped 8-link chain a local ascent
// finds states beyond that, so eq. (12) could be reported as holding on a k_c
// that bounded nothing. The proven k_c bounds every ratio found.
TEST(Bounds, KcBoundsAHeavyTippedEightLinkChainWhereTheSampledValueDidNot) {
  const PlanarChain chain(heavyTipChain());
  const int n = chain.dof();
  std::mt19937_64 rng(20261121);  // the old method, as it was
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  double sampled = 0.0;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  for (int s = 0; s < 20000; ++s) {
    for (int i = 1; i < n; ++i) q(i) = angle(rng);
    sampled = std::max(sampled, coriolisGain(chain, q));
  }
  const double old_kc = 1.05 * sampled, found = coriolisLargestFound(chain),
               kc = coriolisBound(chain).value();
  std::printf("8 links, 10 kg tip: old sampled k_c %.6g, largest found %.6g, proven k_c %.6g\n", old_kc,
              found, kc);
  EXPECT_GT(found, old_kc) << "the old estimate was not exceeded: this chain no longer shows the flaw";
  EXPECT_GE(kc, found);
  // Any state: ||C(q, y)|| <= k_c ||y||.
  std::normal_distribution<double> nd;
  for (int s = 0; s < 2000; ++s) {
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) q(i) = 5 * nd(rng), y(i) = nd(rng);
    EXPECT_LE(lagrange::model::largestSingularValue(chain.coriolis(q, y)), kc * y.norm());
  }
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
  p.model = std::make_shared<PlanarChain>(pelicanParams());
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
