#include "model/theorem3.hpp"

#include <algorithm>
#include <stdexcept>

#include "model/definiteness.hpp"
#include "model/spectra.hpp"
#include "util/error.hpp"

namespace lagrange::model {

namespace {
// prod_{j=from}^{to} beta_j.
double betaProduct(const std::vector<ScalarStage>& s, int from, int to) {
  double p = 1.0;
  for (int j = from; j <= to; ++j) p *= appendixBeta(s, j);
  return p;
}
}  // namespace

double appendixBeta(const std::vector<ScalarStage>& s, int j) {
  return s[j - 1].kp + s[j - 1].b * s[j - 1].kd;
}

double appendixEta(const std::vector<ScalarStage>& s, int i, int k) {
  double bracket = s[k - 1].kp * s[k - 1].kp - s[k - 1].kd * s[k - 1].kd;
  if (k > 1) bracket -= s[k - 1].kp * s[k - 2].kp;
  return betaProduct(s, k + 1, i - 1) * bracket;
}

double appendixMu(const std::vector<ScalarStage>& s, int i, int k) {
  return betaProduct(s, k + 1, i - 1) * s[k - 1].kd * (s[k - 1].kp + s[k - 1].a);
}

Eigen::MatrixXd theorem3A(const std::vector<ScalarStage>& s) {
  const int m = static_cast<int>(s.size());
  Eigen::MatrixXd kp = Eigen::MatrixXd::Zero(m, m), g1 = Eigen::MatrixXd::Zero(m, m),
                  g2 = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd kd(m), sigma(m), b(m), af(m);
  for (int i = 1; i <= m; ++i) {
    kp(i - 1, i - 1) = s[i - 1].kp;
    if (i < m) kp(i - 1, i) = -1.0;
    kd(i - 1) = s[i - 1].kd;
    b(i - 1) = s[i - 1].b;
    af(i - 1) = s[i - 1].a;
    sigma(i - 1) = i == 1 ? 0.0 : s[i - 1].b * s[i - 2].kp;
    if (i >= 2) {
      g1(i - 1, i - 1) = -s[i - 2].kp;
      for (int k = 1; k < i; ++k) {
        g1(i - 1, k - 1) = appendixEta(s, i, k);
        g2(i - 1, k - 1) = -appendixMu(s, i, k);
      }
    }
  }
  Eigen::MatrixXd a(2 * m, 2 * m);
  a.topLeftCorner(m, m) = -(kp + g1);
  a.topRightCorner(m, m) = Eigen::MatrixXd(kd.asDiagonal()) - g2;
  a.bottomLeftCorner(m, m) = -Eigen::MatrixXd((kd - sigma).asDiagonal()) + b.asDiagonal() * g1;
  a.bottomRightCorner(m, m) = -Eigen::MatrixXd(af.asDiagonal()) + b.asDiagonal() * g2;
  return a;
}

Eigen::VectorXd theorem3B(const std::vector<ScalarStage>& s) {
  const int m = static_cast<int>(s.size());
  Eigen::VectorXd out(2 * m);
  for (int i = 1; i <= m; ++i) {
    const double g3 = betaProduct(s, 1, i - 1);  // 1, beta_1, beta_1 beta_2, ...
    out(i - 1) = -g3;
    out(m + i - 1) = s[i - 1].b * g3;
  }
  return out;
}

Eigen::MatrixXd solveLyapunov(const Eigen::MatrixXd& a, const Eigen::MatrixXd& q) {
  const int n = static_cast<int>(a.rows());
  // vec(A^T P + P A) = (I (x) A^T + A^T (x) I) vec(P).
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n * n, n * n);
  const Eigen::MatrixXd at = a.transpose(), eye = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      k.block(i * n, j * n, n, n) += eye(i, j) * at;
      k.block(i * n, j * n, n, n) += at(i, j) * eye;
    }
  const Eigen::VectorXd rhs = -Eigen::Map<const Eigen::VectorXd>(q.data(), n * n);
  // The gains make A badly scaled (its entries span many decades), so judge
  // the solution by its residual, not by a rank threshold.
  const Eigen::VectorXd p = k.fullPivLu().solve(rhs);
  const Eigen::MatrixXd pm = Eigen::Map<const Eigen::MatrixXd>(p.data(), n, n);
  const Eigen::MatrixXd sym = 0.5 * (pm + pm.transpose());
  const double residual = (at * sym + sym * a + q).norm() / q.norm();
  if (!sym.allFinite() || residual > 1e-6)
    throw lagrange::RuntimeFault(
        "the Lyapunov equation A^T P + P A = -Q has no accurate solution (residual " +
        std::to_string(residual) + ")");
  return sym;
}

namespace {
// (786)'s left side for one (P, Q) pair, Jacobi-scaled by Q's diagonal:
// lambda_min(D (Q - e diag{|[P B]_i|^2}) D), D = diag(Q)^(-1/2); same sign as unscaled.
double condition786(const Eigen::MatrixXd& p, const Eigen::MatrixXd& q, const Eigen::VectorXd& b, double e) {
  const Eigen::VectorXd pb = p * b;
  return scaledMinEigenvalue(q - e * Eigen::MatrixXd(pb.cwiseAbs2().asDiagonal()), q);
}
}  // namespace

std::vector<ConditionReport> theorem3Conditions(double kc, double kdelta, const EtaEstimate& eta_estimate,
                                                const Eigen::VectorXd& kd0, const Eigen::VectorXd& a0,
                                                const Eigen::VectorXd& b0,
                                                const std::vector<StageVectors>& stages) {
  const int m = static_cast<int>(stages.size());
  const int joints = static_cast<int>(kd0.size());
  const double e = eta_estimate.eta2 * eta_estimate.eta2 + eta_estimate.eta3 * eta_estimate.eta3;
  double hurwitz = 1e300, lyapunov = 1e300;
  bool all_hurwitz = true, certified = false, unsolved = false;
  for (int j = 0; j < joints; ++j) {
    std::vector<ScalarStage> s;
    for (const auto& st : stages) s.push_back({st.kp(j), st.kd(j), st.a(j), st.b(j)});
    const Eigen::MatrixXd a = theorem3A(s);
    const Eigen::VectorXd b = theorem3B(s);
    // P = I is a Lyapunov matrix when Q = -(A + A^T) > 0: Proposition 1's choice,
    // which also proves A Hurwitz without trusting an eigenvalue solver.
    const Eigen::MatrixXd q_identity_p = -(a + a.transpose());
    const bool identity_works = scaledMinEigenvalue(q_identity_p, q_identity_p) > 0.0;
    const double eig = hurwitzMargin(a);
    hurwitz = std::min(hurwitz, eig);
    certified = certified || (identity_works && eig <= 0.0);
    if (eig <= 0.0 && !identity_works) {
      all_hurwitz = false;
      continue;
    }
    double best = -1e300;
    if (identity_works) best = condition786(Eigen::MatrixXd::Identity(2 * m, 2 * m), q_identity_p, b, e);
    const Eigen::MatrixXd q = Eigen::MatrixXd::Identity(2 * m, 2 * m);
    try {
      const Eigen::MatrixXd p = solveLyapunov(a, q);
      if (symmetricEigenvalues(p).minCoeff() > 0.0) best = std::max(best, condition786(p, q, b, e));
    } catch (const lagrange::RuntimeFault&) {
      unsolved = !identity_works;
    }
    if (best == -1e300) best = -1.0;  // no usable P: the condition cannot be shown to hold
    lyapunov = std::min(lyapunov, best);
  }
  const double low = a0.minCoeff() / b0.maxCoeff(), high = a0.maxCoeff() / b0.minCoeff();
  const double half = (m + 2) / 2.0;
  std::vector<ConditionReport> out;
  ConditionReport hurwitz_report = makeCondition(
      "A Hurwitz (Theorem 6)",
      std::string("-max Re eig(A) > 0 (balanced A, worst joint)") +
          (certified ? "; the eigenvalues are inaccurate here, but -(A + A^T) > 0 proves A Hurwitz" : ""),
      hurwitz, 0.0);
  hurwitz_report.holds = all_hurwitz;
  out.push_back(hurwitz_report);
  out.push_back(makeCondition(
      "eq. (74)", "kd0_min (a0_min / (4 b0_max) - m) > (m+2)/2 + [k_c k_delta + (m+2)/2] (a0_max / b0_min)^2",
      kd0.minCoeff() * (low / 4.0 - m), half + (kc * kdelta + half) * high * high));
  if (all_hurwitz)
    out.push_back(makeCondition(
        "eq. (75)",
        std::string("lambda_min(D (Q - (eta_2^2 + eta_3^2) diag{|[P B]_i|^2}) D) > 0, D = diag(Q)^-1/2, "
                    "the better of P = I with Q = -(A + A^T) and Q = I with P from the Lyapunov equation "
                    "(worst joint)") +
            (unsolved ? "; P could not be computed accurately for this A" : ""),
        lyapunov, 0.0));
  else
    out.push_back(makeCondition("eq. (75)", "needs A Hurwitz first", -1.0, 0.0));
  return out;
}

}  // namespace lagrange::model
