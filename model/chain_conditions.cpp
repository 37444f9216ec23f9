#include "model/chain_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "model/spectra.hpp"

namespace lagrange::model {

namespace {
// D q_d'' + C(q, q_d') q_d' + g at the reference sample r (evaluated to
// order 2): one inverse-dynamics call (a kind without its own computes
// exactly this expression; a URDF arm needs no C for it).
Eigen::VectorXd h(const RobotModel& arm, const ReferenceSample& r, const Eigen::VectorXd& q) {
  return arm.inverseDynamics(q, r.qd(), r.qdd());
}
Eigen::VectorXd h(const RobotModel& arm, const Reference& reference, double t, const Eigen::VectorXd& q) {
  return h(arm, reference.evaluate(t, 2), q);
}

Eigen::MatrixXd dhdq(const RobotModel& arm, const Reference& reference, double t, const Eigen::VectorXd& q) {
  const int n = arm.dof();
  const double step = 1e-6;
  const ReferenceSample r = reference.evaluate(t, 2);  // once: every column is at the same t
  Eigen::MatrixXd j(n, n);
  for (int k = 0; k < n; ++k) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, k) * step;
    j.col(k) = (h(arm, r, q + e) - h(arm, r, q - e)) / (2 * step);
  }
  return j;
}

double horizon(const Reference& reference) {
  const ReferenceParams& p = reference.params();
  if (p.type == ReferenceType::kFreeMotion) return p.horizon;  // all of it
  double longest = 0.0, settle = 0.0;
  for (int i = 0; i < reference.dof(); ++i) {
    if (p.frequency(i) > 0.0) longest = std::max(longest, 2.0 * M_PI / p.frequency(i));
    if (p.type == ReferenceType::kSmoothSine)
      settle = std::max(settle, std::cbrt(std::log(1e12) / p.alpha(i)));
  }
  return std::max(10.0, 2.0 * longest + settle);
}

// Compass search maximising value(t, q) from (t, q): a step up along t or any
// q_i is taken, the step halves when none is, down to 1e-7 (t scaled by
// t_scale). `allowed` rejects points outside the search's domain.
template <class Value, class Allowed>
double ascend(double t, Eigen::VectorXd q, double value_at_start, double t_max, double t_scale, Value value,
              Allowed allowed) {
  double best = value_at_start;
  const int n = static_cast<int>(q.size());
  for (double step = 0.05; step > 1e-7;) {
    bool moved = false;
    for (int axis = 0; axis <= n; ++axis) {
      for (const double sign : {1.0, -1.0}) {
        double trial_t = t;
        Eigen::VectorXd trial_q = q;
        if (axis == n) {
          trial_t = std::clamp(t + sign * step * t_scale, 1e-6, t_max);
        } else {
          trial_q(axis) += sign * step;
        }
        if (!allowed(trial_t, trial_q)) continue;
        const double v = value(trial_t, trial_q);
        if (v > best) best = v, t = trial_t, q = trial_q, moved = true;
      }
    }
    if (!moved) step /= 2.0;
  }
  return best;
}

}  // namespace

EtaEstimate estimateEta(const RobotModel& arm, const Reference& reference, const Eigen::VectorXd& kp0,
                        const Eigen::VectorXd& kd0, const Eigen::VectorXd& a0, const Eigen::VectorXd& b0) {
  const int n = arm.dof();
  EtaEstimate eta;
  eta.eta3 = (kd0.array() * a0.array()).maxCoeff();
  const Eigen::MatrixXd damping = (kp0.array() + kd0.array() * b0.array()).matrix().asDiagonal();
  std::mt19937_64 rng(632);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  const double t_max = horizon(reference), dt = 1e-6;
  const double t_last = t_max + dt;  // the sampled t run up to it; dhdt needs t - dt >= 0
  // Both ratios rest on dh/dq at (t, q) (2 n inverse-dynamics calls): the
  // sampling below computes it once for the two.
  auto eta2_from = [&](const Eigen::MatrixXd& jacobian) { return largestSingularValue(jacobian - damping); };
  auto eta1_from = [&](const Eigen::MatrixXd& jacobian, double t, const Eigen::VectorXd& q) {
    const ReferenceSample r = reference.evaluate(t, 1);
    const Eigen::VectorXd dhdt = (h(arm, reference, t + dt, q) - h(arm, reference, t - dt, q)) / (2 * dt);
    return (jacobian * r.qd() + dhdt).norm() / std::min((q - r.q()).norm(), 1.0);
  };
  auto eta2_at = [&](double t, const Eigen::VectorXd& q) { return eta2_from(dhdq(arm, reference, t, q)); };
  auto eta1_at = [&](double t, const Eigen::VectorXd& q) {
    return eta1_from(dhdq(arm, reference, t, q), t, q);
  };
  // The kStarts best samples of each, largest first: the starts of the ascent.
  struct Sample {
    double value = -1.0, t = 0.0;
    Eigen::VectorXd q;
  };
  constexpr size_t kStarts = 8;
  std::vector<Sample> best1, best2;
  auto keep = [](std::vector<Sample>& best, double value, double t, const Eigen::VectorXd& q) {
    if (best.size() == kStarts && value <= best.back().value) return;
    const auto at = std::find_if(best.begin(), best.end(), [&](const Sample& s) { return value > s.value; });
    best.insert(at, Sample{value, t, q});
    if (best.size() > kStarts) best.pop_back();
  };
  for (int it = 0; it < 400; ++it) {
    const double t = t_max * it / 399.0 + dt;
    const ReferenceSample r = reference.evaluate(t, 1);
    for (double radius : {1e-2, 1e-1, 1.0, 10.0}) {
      for (int d = 0; d < 4; ++d) {
        Eigen::VectorXd dir(n);
        for (int i = 0; i < n; ++i) dir(i) = normal(rng);
        const Eigen::VectorXd q = r.q() + radius * dir.normalized();
        const Eigen::MatrixXd jacobian = dhdq(arm, reference, t, q);
        keep(best2, eta2_from(jacobian), t, q);
        keep(best1, eta1_from(jacobian, t, q), t, q);
      }
    }
    for (int d = 0; d < 4; ++d) {
      Eigen::VectorXd q(n);
      for (int i = 0; i < n; ++i) q(i) = angle(rng);
      keep(best2, eta2_at(t, q), t, q);
    }
  }
  // Local ascent from the best samples of each. eta_1 keeps |q - q_d| >= 1e-2,
  // the smallest sampled radius: off a free motion its ratio grows without
  // bound as q -> q_d (the header says why), and no ascent should chase that.
  const double t_scale = t_max / 399.0;
  auto anywhere = [](double, const Eigen::VectorXd&) { return true; };
  auto off_reference = [&](double t, const Eigen::VectorXd& q) {
    return (q - reference.evaluate(t, 0).q()).norm() >= 1e-2;
  };
  for (const Sample& s : best2)
    eta.eta2 = std::max(eta.eta2, ascend(s.t, s.q, s.value, t_last, t_scale, eta2_at, anywhere));
  for (const Sample& s : best1)
    eta.eta1 = std::max(eta.eta1, ascend(s.t, s.q, s.value, t_last, t_scale, eta1_at, off_reference));
  eta.eta1 *= 1.1;
  eta.eta2 *= 1.1;
  return eta;
}

std::vector<ConditionReport> theorem2Conditions(double kc, double kdelta, const EtaEstimate& eta,
                                                const Eigen::VectorXd& kd0, const Eigen::VectorXd& a0,
                                                const Eigen::VectorXd& b0, const Eigen::VectorXd& kp1,
                                                const Eigen::VectorXd& a1, const Eigen::VectorXd& b1) {
  const double ratio_low = a0.minCoeff() / b0.maxCoeff(), ratio_high = a0.maxCoeff() / b0.minCoeff();
  const double e2 = eta.eta2 * eta.eta2, e3 = eta.eta3 * eta.eta3;
  return {
      makeCondition(
          "eq. (56a)", "kd0_min (a0_min / (4 b0_max) - 1) > 3/2 + (k_c k_delta + 3/2) (a0_max / b0_min)^2",
          kd0.minCoeff() * (ratio_low / 4.0 - 1.0), 1.5 + (kc * kdelta + 1.5) * ratio_high * ratio_high),
      makeCondition("eq. (56b)", "kp1_min > (eta_2^2 + eta_3^2) / 2 + 2", kp1.minCoeff(),
                    0.5 * (e2 + e3) + 2.0),
      // As printed, (632c) reads a1 > (eta_2^2 + eta_3^2 b1^2 + 1) / 2; the proof's
      // own bound (700) and the alpha_3 before (745) need b1^2 on eta_2^2 too.
      makeCondition("eq. (56c)", "a1_min > (b1_max^2 (eta_2^2 + eta_3^2) + 1) / 2 (corrected reading)",
                    a1.minCoeff(), 0.5 * (b1.maxCoeff() * b1.maxCoeff() * (e2 + e3) + 1.0)),
  };
}

}  // namespace lagrange::model
