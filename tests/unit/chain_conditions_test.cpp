// Theorem 2's gain conditions (632a-c) and the eta estimates of bound (650).
#include "model/chain_conditions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "model/planar_chain.hpp"
#include "model/spectra.hpp"

namespace lagrange::model {
namespace {

Eigen::VectorXd v2(double a, double b) { return Eigen::Vector2d(a, b); }

TEST(Theorem2Conditions, EachPassesOrFailsByItsOwnInequality) {
  const EtaEstimate eta{5.0, 2.0, 3.0};
  // A gain set that satisfies all three: a0/b0 = 40 and kd0 = 300 (the right side of
  // (632a) is 1.5 + 1.52 * 40^2 = 2433.5), kp1 and a1 above their bounds.
  auto all = theorem2Conditions(0.02, 1.0, eta, v2(300, 320), v2(400, 400), v2(10, 10), v2(10, 12),
                                v2(60, 70), v2(2, 2));
  ASSERT_EQ(all.size(), 3u);
  for (const auto& c : all) EXPECT_TRUE(c.holds) << c.name << " " << c.lhs << " > " << c.rhs;
  EXPECT_DOUBLE_EQ(all[1].rhs, 0.5 * (4.0 + 9.0) + 2.0);          // (632b)
  EXPECT_DOUBLE_EQ(all[2].rhs, 0.5 * (4.0 * (4.0 + 9.0) + 1.0));  // (632c) with b1_max = 2
  EXPECT_DOUBLE_EQ(all[0].lhs, 300.0 * (400.0 / 40.0 - 1.0));     // (632a): kd0_min (a0/(4 b0) - 1)

  // Violate one at a time.
  auto a = theorem2Conditions(0.02, 1.0, eta, v2(300, 320), v2(20, 400), v2(10, 10), v2(10, 12), v2(60, 70),
                              v2(2, 2));
  EXPECT_FALSE(a[0].holds);  // a0_min / (4 b0_max) = 0.5: the bracket is negative
  EXPECT_EQ(a[0].name, "eq. (56a)");
  EXPECT_TRUE(a[1].holds && a[2].holds);
  auto b = theorem2Conditions(0.02, 1.0, eta, v2(300, 320), v2(400, 400), v2(10, 10), v2(8.4, 12), v2(60, 70),
                              v2(2, 2));
  EXPECT_FALSE(b[1].holds);  // kp1_min = 8.4 < 8.5
  EXPECT_EQ(b[1].name, "eq. (56b)");
  EXPECT_TRUE(b[0].holds && b[2].holds);
  auto c = theorem2Conditions(0.02, 1.0, eta, v2(300, 320), v2(400, 400), v2(10, 10), v2(10, 12),
                              v2(26.4, 70), v2(2, 2));
  EXPECT_FALSE(c[2].holds);  // a1_min = 26.4 < 26.5
  EXPECT_EQ(c[2].name, "eq. (56c)");
  EXPECT_LT(c[2].margin(), 0.0);
}

// (632c) as printed, a1 > (eta_2^2 + eta_3^2 b1^2 + 1) / 2, lacks b1^2 on
// eta_2^2 (compare the proof's (700) and (795c) at i = 1). With b1 = 2,
// eta_2 = 2, eta_3 = 3 the printed bound is 20.5 and the corrected 26.5: a1 = 23
// passes the printed form and must fail.
TEST(Theorem2Conditions, Eq632cCarriesB1SquaredOnEta2) {
  const EtaEstimate eta{5.0, 2.0, 3.0};
  const double b1 = 2.0, printed = 0.5 * (4.0 + 9.0 * b1 * b1 + 1.0),
               corrected = 0.5 * (b1 * b1 * 13.0 + 1.0);
  ASSERT_LT(printed, 23.0);
  ASSERT_GT(corrected, 23.0);
  const auto r = theorem2Conditions(0.02, 1.0, eta, v2(300, 320), v2(400, 400), v2(10, 10), v2(10, 12),
                                    v2(23, 70), v2(b1, b1));
  EXPECT_FALSE(r[2].holds);
  EXPECT_DOUBLE_EQ(r[2].rhs, corrected);
  // With b1 = 1 both readings agree.
  const auto unit = theorem2Conditions(0.02, 1.0, eta, v2(300, 320), v2(400, 400), v2(10, 10), v2(10, 12),
                                       v2(23, 70), v2(1, 1));
  EXPECT_TRUE(unit[2].holds);
  EXPECT_DOUBLE_EQ(unit[2].rhs, 0.5 * (4.0 + 9.0 + 1.0));
}

TEST(EtaEstimate, Eta3IsExactAndEta2BoundsTheJacobianTerm) {
  const PlanarChain chain(pelicanParams());
  ReferenceParams p;
  p.type = ReferenceType::kSine;
  p.offset = v2(0.3, 0.2);
  p.amplitude = v2(0.2, 0.1);
  p.frequency = v2(2.0, 3.0);
  p.phase = v2(0.0, 0.0);
  const Reference reference(p);
  const Eigen::VectorXd kp0 = v2(40, 10), kd0 = v2(5, 1), a0 = v2(60, 30), b0 = v2(50, 20);
  const EtaEstimate eta = estimateEta(chain, reference, kp0, kd0, a0, b0);
  EXPECT_DOUBLE_EQ(eta.eta3, 300.0);  // max(kd0 a0)
  // eta_2 >= ||dh/dq - diag(kp0 + kd0 b0)|| >= its value without dh/dq's help at
  // a point where dh/dq is small relative to the damping: 290 - ||dh/dq||.
  EXPECT_GT(eta.eta2, 250.0);
  EXPECT_LT(eta.eta2, 400.0);  // and not uselessly loose: dh/dq of the Pelican is a few N m/rad
  EXPECT_GT(eta.eta1, 0.0);
}

// eta_2 is a sampled supremum: the local ascent must carry it at least to the
// largest value a much denser, independent sampling finds (before the 1.1
// margin; printed, so a regression shows by how much).
TEST(EtaEstimate, Eta2ReachesTheLargestValueADenseSamplingFinds) {
  ChainParams params;
  params.links = {{0.3, 0.15, 3.0, 0.02}, {0.3, 0.1, 2.0, 0.015}, {0.2, 0.1, 4.0, 0.004}};
  const PlanarChain chain(params);
  ReferenceParams p;
  p.type = ReferenceType::kSine;
  p.offset = Eigen::Vector3d(0.3, 0.2, -0.4);
  p.amplitude = Eigen::Vector3d(0.5, 0.8, 1.0);
  p.frequency = Eigen::Vector3d(2.0, 3.0, 5.0);
  p.phase = Eigen::Vector3d(0.0, 0.5, 1.0);
  const Reference reference(p);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(3);
  const Eigen::VectorXd kp0 = 2 * ones, kd0 = ones, a0 = 3 * ones, b0 = 3 * ones;
  const EtaEstimate eta = estimateEta(chain, reference, kp0, kd0, a0, b0);
  const Eigen::MatrixXd damping = (kp0 + kd0.cwiseProduct(b0)).asDiagonal();
  auto hAt = [&](double t, const Eigen::VectorXd& q) {
    const ReferenceSample r = reference.evaluate(t, 2);
    return Eigen::VectorXd(chain.inertia(q) * r.qdd() + chain.coriolis(q, r.qd()) * r.qd() +
                           chain.gravity(q));
  };
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> time(0.0, 10.0), angle(0.0, 2.0 * M_PI);
  double dense = 0.0;
  for (int s = 0; s < 40000; ++s) {
    const double t = time(rng);
    Eigen::VectorXd q(3);
    for (int i = 0; i < 3; ++i) q(i) = angle(rng);
    Eigen::MatrixXd j(3, 3);
    for (int k = 0; k < 3; ++k) {
      const Eigen::VectorXd e = Eigen::VectorXd::Unit(3, k) * 1e-6;
      j.col(k) = (hAt(t, q + e) - hAt(t, q - e)) / 2e-6;
    }
    dense = std::max(dense, lagrange::model::largestSingularValue(j - damping));
  }
  std::printf("eta_2 / 1.1 = %.6g, densest sampling's largest %.6g\n", eta.eta2 / 1.1, dense);
  EXPECT_GE(eta.eta2 / 1.1, dense * (1.0 - 1e-6));
}

}  // namespace
}  // namespace lagrange::model
