// The cascaded controller of eq. (750): exact discretisation of its filters,
// and its algebra against the paper's error equations (760), the recursion
// for xi*_{i+1}' and the Appendix's closed form (771) with eta_ik, mu_ik and
// beta_j, on the closed loop of the Pelican arm, m = 1..4.
#include "controller/cascaded.hpp"

#include <gtest/gtest.h>

#include <random>

#include "model/theorem3.hpp"
#include "support/rk4.hpp"

namespace lagrange::controller {
namespace {

CascadedGains gainsFor(int m, int n) {
  CascadedGains g;
  g.stage0 = {Eigen::VectorXd::Constant(n, 40.0), Eigen::VectorXd::Constant(n, 4.0),
              Eigen::VectorXd::Constant(n, 60.0), Eigen::VectorXd::Constant(n, 50.0)};
  for (int i = 0; i < m; ++i) {
    // Different numbers per stage and joint, so an index mix-up shows.
    StageGains s;
    s.kp = Eigen::VectorXd::LinSpaced(n, 3.0 + i, 4.0 + i);
    s.kd = Eigen::VectorXd::LinSpaced(n, 1.5 + 0.5 * i, 2.0 + 0.3 * i);
    s.a = Eigen::VectorXd::LinSpaced(n, 20.0 + 5 * i, 30.0 + 5 * i);
    s.b = Eigen::VectorXd::LinSpaced(n, 0.7 + 0.1 * i, 0.9 + 0.1 * i);
    g.stages.push_back(s);
  }
  return g;
}

Eigen::MatrixXd randomMatrix(std::mt19937_64& rng, int rows, int cols, double scale) {
  std::uniform_real_distribution<double> d(-scale, scale);
  Eigen::MatrixXd x(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) x(i, j) = d(rng);
  return x;
}

TEST(Cascade, SigmaIsZeroForTheFirstStageThenBTimesThePreviousKp) {
  const CascadedGains g = gainsFor(3, 2);
  EXPECT_EQ(cascadeSigma(g, 1), Eigen::Vector2d::Zero());
  EXPECT_EQ(cascadeSigma(g, 2), g.stages[1].b.cwiseProduct(g.stages[0].kp));
  EXPECT_EQ(cascadeSigma(g, 3), g.stages[2].b.cwiseProduct(g.stages[1].kp));
}

class CascadeOrder : public ::testing::TestWithParam<int> {};

// advanceCascade equals RK4 of eqs. (750c, 750d) with xi* and xit held.
TEST_P(CascadeOrder, AdvanceIsExactForHeldSignals) {
  const int m = GetParam(), n = 2;
  const CascadedGains g = gainsFor(m, n);
  std::mt19937_64 rng(m);
  CascadeSignals held;
  held.xi_star = randomMatrix(rng, m, n, 3.0);
  held.xi_error = randomMatrix(rng, m, n, 2.0);
  CascadeState exact{randomMatrix(rng, m, n, 1.0), randomMatrix(rng, m, n, 1.0)};
  CascadeState start = exact;
  const double dt = 0.02;  // a dt up to 0.8: far from Euler's regime
  advanceCascade(g, held, dt, exact);

  // Pack (qc, zeta) and integrate with theta recomputed from the state.
  auto pack = [&](const CascadeState& s) {
    Eigen::VectorXd v(2 * m * n);
    v << Eigen::Map<const Eigen::VectorXd>(s.qc.data(), m * n),
        Eigen::Map<const Eigen::VectorXd>(s.zeta.data(), m * n);
    return v;
  };
  auto f = [&](double, const Eigen::VectorXd& v) {
    CascadeState s{Eigen::Map<const Eigen::MatrixXd>(v.data(), m, n),
                   Eigen::Map<const Eigen::MatrixXd>(v.data() + m * n, m, n)};
    CascadeSignals sig = held;
    sig.theta.resize(m, n);
    for (int i = 0; i < m; ++i)
      sig.theta.row(i) = s.qc.row(i) +
                         g.stages[i].b.cwiseProduct(held.xi_star.row(i).transpose()).transpose() +
                         s.zeta.row(i);
    return pack(cascadeDerivative(g, sig));
  };
  Eigen::VectorXd v = pack(start);
  for (int k = 0; k < 2000; ++k) v = testing::rk4Step(f, 0.0, v, dt / 2000);
  EXPECT_LT((pack(exact) - v).norm(), 1e-10 * (1 + v.norm()));
}

// The closed loop of eqs. (600), (610a), (750) in continuous time, state
// X = [q, q', qc0, xi (m x n), qc (m x n), zeta (m x n)]; the derivatives of
// xit_i, theta_i and xi_i* along it are taken by central differences and
// compared with eqs. (760a), (760b) and the recursion for xi*_{i+1}' (771).
TEST_P(CascadeOrder, AlgebraMatchesTheErrorEquations760) {
  const int m = GetParam(), n = 2;
  const model::PlanarChain chain(model::pelicanParams());
  model::ReferenceParams rp;
  rp.type = model::ReferenceType::kSine;
  rp.offset = Eigen::Vector2d(0.3, -0.2);
  rp.amplitude = Eigen::Vector2d(0.4, 0.3);
  rp.frequency = Eigen::Vector2d(1.5, 2.0);
  rp.phase = Eigen::Vector2d(0.1, 0.4);
  const model::Reference reference(rp);
  const CascadedGains g = gainsFor(m, n);
  const Theorem1Controller law(chain, reference, g.stage0, std::nullopt);
  const int size = 3 * n + 3 * m * n;

  struct Unpacked {
    Eigen::VectorXd q, v, qc0;
    Eigen::MatrixXd xi;
    CascadeState cascade;
  };
  auto unpack = [&](const Eigen::VectorXd& x) {
    Unpacked u;
    u.q = x.segment(0, n);
    u.v = x.segment(n, n);
    u.qc0 = x.segment(2 * n, n);
    u.xi = Eigen::Map<const Eigen::MatrixXd>(x.data() + 3 * n, m, n);
    u.cascade.qc = Eigen::Map<const Eigen::MatrixXd>(x.data() + 3 * n + m * n, m, n);
    u.cascade.zeta = Eigen::Map<const Eigen::MatrixXd>(x.data() + 3 * n + 2 * m * n, m, n);
    return u;
  };
  auto signals = [&](double t, const Eigen::VectorXd& x, Eigen::VectorXd* theta0 = nullptr) {
    const Unpacked u = unpack(x);
    const model::ReferenceSample r = reference.evaluate(t, 2);
    const Eigen::VectorXd th0 = u.qc0 + g.stage0.b.cwiseProduct(u.q - r.q());
    if (theta0) *theta0 = th0;
    return evaluateCascade(g, law.law(r, u.q, th0), u.xi, u.cascade);
  };
  auto field = [&](double t, const Eigen::VectorXd& x) {
    const Unpacked u = unpack(x);
    Eigen::VectorXd theta0;
    const CascadeSignals s = signals(t, x, &theta0);
    const CascadeState d = cascadeDerivative(g, s);
    Eigen::VectorXd dx(size);
    dx.segment(0, n) = u.v;
    dx.segment(n, n) = chain.acceleration(u.q, u.v, u.xi.row(0).transpose());
    dx.segment(2 * n, n) = -g.stage0.a.cwiseProduct(theta0);
    Eigen::MatrixXd dxi(m, n);
    for (int i = 0; i + 1 < m; ++i) dxi.row(i) = u.xi.row(i + 1);
    dxi.row(m - 1) = s.u.transpose();
    dx.segment(3 * n, m * n) = Eigen::Map<const Eigen::VectorXd>(dxi.data(), m * n);
    dx.segment(3 * n + m * n, m * n) = Eigen::Map<const Eigen::VectorXd>(d.qc.data(), m * n);
    dx.segment(3 * n + 2 * m * n, m * n) = Eigen::Map<const Eigen::VectorXd>(d.zeta.data(), m * n);
    return dx;
  };

  std::mt19937_64 rng(100 + m);
  for (int trial = 0; trial < 5; ++trial) {
    const double t = 0.3 + trial;
    const Eigen::VectorXd x = randomMatrix(rng, size, 1, 1.0).col(0);
    const Eigen::VectorXd fx = field(t, x);
    const double h = 1e-6;
    const CascadeSignals now = signals(t, x), ahead = signals(t + h, x + h * fx),
                         back = signals(t - h, x - h * fx);
    auto rate = [&](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) -> Eigen::MatrixXd {
      return (a - b) / (2 * h);
    };
    const Eigen::MatrixXd xit_dot = rate(ahead.xi_error, back.xi_error);
    const Eigen::MatrixXd theta_dot = rate(ahead.theta, back.theta);
    const Eigen::MatrixXd star_dot = rate(ahead.xi_star, back.xi_star);
    for (int i = 0; i < m; ++i) {
      const StageGains& s = g.stages[i];
      const Eigen::VectorXd xit = now.xi_error.row(i).transpose(), th = now.theta.row(i).transpose();
      const Eigen::VectorXd sd = star_dot.row(i).transpose();
      Eigen::VectorXd e760a = -s.kp.cwiseProduct(xit) + s.kd.cwiseProduct(th) - sd;
      if (i + 1 < m) e760a += now.xi_error.row(i + 1).transpose();
      const Eigen::VectorXd e760b =
          -s.a.cwiseProduct(th) - (s.kd - cascadeSigma(g, i + 1)).cwiseProduct(xit) + s.b.cwiseProduct(sd);
      const double tol = 1e-5 * (1 + fx.norm());
      EXPECT_LT((xit_dot.row(i).transpose() - e760a).norm(), tol) << "eq. (760a), stage " << i + 1;
      EXPECT_LT((theta_dot.row(i).transpose() - e760b).norm(), tol) << "eq. (760b), stage " << i + 1;
      if (i + 1 < m) {
        // xi*_{i+1}' = [kp^2 - kd^2 + kd sigma] xit_i - kd (kp + a) theta_i - kp xit_{i+1} + (kp + kd b)
        // xi_i*'
        const Eigen::VectorXd sigma = cascadeSigma(g, i + 1);
        const Eigen::VectorXd recursion =
            (s.kp.array().square() - s.kd.array().square() + s.kd.array() * sigma.array())
                .matrix()
                .cwiseProduct(xit) -
            s.kd.cwiseProduct(s.kp + s.a).cwiseProduct(th) -
            s.kp.cwiseProduct(now.xi_error.row(i + 1).transpose()) +
            (s.kp + s.kd.cwiseProduct(s.b)).cwiseProduct(sd);
        EXPECT_LT((star_dot.row(i + 1).transpose() - recursion).norm(), tol)
            << "recursion (771), stage " << i + 1;
      }
    }
    // The Appendix's closed form, for i = 2..m (1-based):
    //   xi_i*' = -kp_{i-1} xit_i + sum_{k<i} (eta_ik xit_k - mu_ik theta_k) + prod_{j<i} beta_j xi_1*'
    //   beta_j = kp_j + b_j kd_j,  P_ik = prod_{j=k+1}^{i-1} beta_j,
    //   eta_ik = P_ik [kp_k^2 - kd_k^2 - kp_k kp_{k-1} sgn(k-1)],  mu_ik = P_ik kd_k (kp_k + a_k).
    // (eq. 771: beta_j^sgn(i-j) makes the j = i factor 1.)
    auto stage = [&](int k) -> const StageGains& { return g.stages[k - 1]; };
    auto beta = [&](int j) {
      return Eigen::ArrayXd(stage(j).kp.array() + stage(j).b.array() * stage(j).kd.array());
    };
    for (int i = 2; i <= m; ++i) {
      Eigen::ArrayXd closed = -stage(i - 1).kp.array() * now.xi_error.row(i - 1).transpose().array();
      for (int k = 1; k < i; ++k) {
        Eigen::ArrayXd p = Eigen::ArrayXd::Ones(n);
        for (int j = k + 1; j <= i - 1; ++j) p *= beta(j);
        Eigen::ArrayXd bracket = stage(k).kp.array().square() - stage(k).kd.array().square();
        if (k > 1) bracket -= stage(k).kp.array() * stage(k - 1).kp.array();
        const Eigen::ArrayXd eta = p * bracket;
        const Eigen::ArrayXd mu = p * stage(k).kd.array() * (stage(k).kp.array() + stage(k).a.array());
        closed +=
            eta * now.xi_error.row(k - 1).transpose().array() - mu * now.theta.row(k - 1).transpose().array();
      }
      Eigen::ArrayXd product = Eigen::ArrayXd::Ones(n);
      for (int j = 1; j < i; ++j) product *= beta(j);
      closed += product * star_dot.row(0).transpose().array();
      EXPECT_LT((star_dot.row(i - 1).transpose() - closed.matrix()).norm(), 1e-5 * (1 + fx.norm()))
          << "Appendix closed form (771), i = " << i;
    }
    // Eq. (787): chi' = A chi + B xi_1*' per joint, chi = [xit_1..m, theta_1..m],
    // with Theorem 3's A and B (model/theorem3.hpp).
    for (int j = 0; j < n; ++j) {
      std::vector<model::ScalarStage> scalar;
      for (const auto& st : g.stages) scalar.push_back({st.kp(j), st.kd(j), st.a(j), st.b(j)});
      Eigen::VectorXd chi(2 * m), chi_dot(2 * m);
      chi << now.xi_error.col(j), now.theta.col(j);
      chi_dot << xit_dot.col(j), theta_dot.col(j);
      const Eigen::VectorXd predicted =
          model::theorem3A(scalar) * chi + model::theorem3B(scalar) * star_dot(0, j);
      EXPECT_LT((chi_dot - predicted).norm(), 1e-5 * (1 + fx.norm())) << "eq. (787), joint " << j;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Orders, CascadeOrder, ::testing::Values(1, 2, 3, 4));

TEST(CascadedController, StepAdvancesTheFiltersThenEvaluatesAndChecksSizes) {
  const model::PlanarChain chain(model::pelicanParams());
  model::ReferenceParams rp;
  rp.type = model::ReferenceType::kSine;
  rp.offset = rp.amplitude = rp.frequency = rp.phase = Eigen::Vector2d::Zero();
  const model::Reference reference(rp);
  const CascadedGains g = gainsFor(2, 2);
  CascadedController ctl(chain, reference, g, std::nullopt);
  const Eigen::MatrixXd xi = Eigen::MatrixXd::Constant(2, 2, 0.5);
  const auto first = ctl.step(0.0, Eigen::Vector2d(0.2, -0.1), xi);
  EXPECT_EQ(ctl.state().qc, Eigen::MatrixXd::Zero(2, 2));  // nothing to advance yet
  CascadeState expected = ctl.state();
  advanceCascade(g, first.cascade, 0.001, expected);
  const auto second = ctl.step(0.001, Eigen::Vector2d(0.2, -0.1), xi);
  EXPECT_LT((ctl.state().qc - expected.qc).norm(), 1e-15);
  EXPECT_LT((ctl.state().zeta - expected.zeta).norm(), 1e-15);
  EXPECT_LT((second.cascade.xi_star.row(0).transpose() - second.stage0.u).norm(),
            1e-15);  // xi_1* = eq. (610a)
  EXPECT_THROW(ctl.step(0.002, Eigen::Vector2d::Zero(), Eigen::MatrixXd::Zero(3, 2)), std::invalid_argument);
  CascadedGains none = g;
  none.stages.clear();
  EXPECT_THROW(CascadedController(chain, reference, none, std::nullopt), std::invalid_argument);
  CascadedGains bad = g;
  bad.stages[1].kd(0) = 0.0;
  EXPECT_THROW(CascadedController(chain, reference, bad, std::nullopt), std::invalid_argument);
}

// Stage starts: bumpless gives theta_i(t0) = 0 on every stage, so the first
// command carries no kick kd_i b_i xi_i*; zeros (the default) give theta_i(t0)
// = b_i xi_i*(t0); given values are used as they are.
TEST(CascadedController, StagesStartBumplessOrFromGivenValues) {
  const model::PlanarChain chain(model::pelicanParams());
  model::ReferenceParams rp;
  rp.type = model::ReferenceType::kSine;
  rp.offset = Eigen::Vector2d(0.3, 0.2);
  rp.amplitude = rp.frequency = rp.phase = Eigen::Vector2d::Zero();
  const model::Reference reference(rp);
  const CascadedGains g = gainsFor(3, 2);
  const Eigen::Vector2d q(1.0, -0.5);
  const Eigen::MatrixXd xi = Eigen::MatrixXd::Zero(3, 2);
  CascadedController zeros(chain, reference, g, std::nullopt);
  const auto z = zeros.step(0.0, q, xi);
  for (int i = 0; i < 3; ++i)
    EXPECT_LT(
        (z.cascade.theta.row(i) - g.stages[i].b.transpose().cwiseProduct(z.cascade.xi_star.row(i))).norm(),
        1e-12);
  std::vector<StageStart> starts(3);
  for (auto& st : starts) st.bumpless = true;
  starts[1].zeta = Eigen::Vector2d(0.7, -0.2);  // bumpless whatever zeta starts at
  CascadedController bumpless(chain, reference, g, std::nullopt, starts);
  const auto b = bumpless.step(0.0, q, xi);
  EXPECT_LT(b.cascade.theta.norm(), 1e-12);
  EXPECT_EQ(bumpless.state().zeta.row(1), Eigen::RowVector2d(0.7, -0.2));
  EXPECT_LT(b.cascade.u.norm(), z.cascade.u.norm());  // no filter kick
  std::vector<StageStart> given(3);
  given[2].qc = Eigen::Vector2d(5.0, -3.0);
  CascadedController valued(chain, reference, g, std::nullopt, given);
  valued.step(0.0, q, xi);
  EXPECT_EQ(valued.state().qc.row(2), Eigen::RowVector2d(5.0, -3.0));
  EXPECT_THROW(CascadedController(chain, reference, g, std::nullopt, std::vector<StageStart>(2)),
               std::invalid_argument);
}

}  // namespace
}  // namespace lagrange::controller
