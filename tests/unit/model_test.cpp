// Property tests of the planar-chain model on random states (fixed seed):
// those of every robot kind (tests/support/robot_model_properties.hpp) and its own,
// and the Pelican arm against the closed form of Kelly et al.'s book.
#include <gtest/gtest.h>

#include <random>

#include "model/planar_chain.hpp"
#include "support/robot_model_properties.hpp"

namespace lagrange::model {
namespace {

ChainParams randomChain(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0.1, 1.0);
  ChainParams p;
  for (int i = 0; i < n; ++i) {
    const double l = u(rng);
    p.links.push_back({l, l * u(rng), 5 * u(rng), 0.1 * u(rng)});
  }
  return p;
}

using testing::randomVector;

class ChainProperties : public ::testing::TestWithParam<int> {};

TEST_P(ChainProperties, HoldOnRandomStates) {
  const int n = GetParam();
  std::mt19937_64 rng(42 + n);
  for (int trial = 0; trial < 100; ++trial) {
    const PlanarChain chain(randomChain(rng, n));
    testing::expectRobotModelProperties(chain, rng);
    const Eigen::VectorXd q = randomVector(rng, n, 10.0);
    const double h = 1e-6;
    // Analytic inertia partials agree with a finite difference.
    const auto partials = chain.inertiaPartials(q);
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd e = Eigen::VectorXd::Unit(n, k) * h;
      const Eigen::MatrixXd fd = (chain.inertia(q + e) - chain.inertia(q - e)) / (2 * h);
      EXPECT_LT((fd - partials[k]).norm(), 1e-6 * (1 + fd.norm()));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Dof, ChainProperties, ::testing::Values(1, 2, 3, 5, 8));

TEST(Pelican, MatchesTheBookClosedForm) {
  const PlanarChain chain(pelicanParams());
  const double l1 = 0.26, lc1 = 0.0983, lc2 = 0.0229, m1 = 6.5225, m2 = 2.0458, i1 = 0.1213, i2 = 0.01616,
               g = 9.81;
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::VectorXd q = randomVector(rng, 2, 7.0), v = randomVector(rng, 2, 4.0);
    const double c2 = std::cos(q(1)), s2 = std::sin(q(1));
    Eigen::Matrix2d d;
    d(0, 0) = m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2 + 2 * l1 * lc2 * c2) + i1 + i2;
    d(0, 1) = d(1, 0) = m2 * (lc2 * lc2 + l1 * lc2 * c2) + i2;
    d(1, 1) = m2 * lc2 * lc2 + i2;
    Eigen::Matrix2d c;
    const double h = m2 * l1 * lc2 * s2;
    c << -h * v(1), -h * (v(0) + v(1)), h * v(0), 0.0;
    Eigen::Vector2d gv;
    gv << (m1 * lc1 + m2 * l1) * g * std::sin(q(0)) + m2 * lc2 * g * std::sin(q(0) + q(1)),
        m2 * lc2 * g * std::sin(q(0) + q(1));
    EXPECT_LT((chain.inertia(q) - d).norm(), 1e-12);
    EXPECT_LT((chain.coriolis(q, v) - c).norm(), 1e-12);
    EXPECT_LT((chain.gravity(q) - gv).norm(), 1e-12);
  }
}

TEST(PlanarChain, RejectsBadParametersAndSizes) {
  ChainParams p = pelicanParams();
  p.links[1].mass = 0.0;
  EXPECT_THROW(PlanarChain{p}, std::invalid_argument);
  p = pelicanParams();
  p.links[0].inertia = -1.0;
  EXPECT_THROW(PlanarChain{p}, std::invalid_argument);
  EXPECT_THROW(PlanarChain{ChainParams{}}, std::invalid_argument);
  const PlanarChain chain(pelicanParams());
  EXPECT_THROW(chain.inertia(Eigen::VectorXd::Zero(3)), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange::model
