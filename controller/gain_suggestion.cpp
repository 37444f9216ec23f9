#include "controller/gain_suggestion.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "controller/paper_section.hpp"
#include "model/bounds.hpp"
#include "model/chain_conditions.hpp"
#include "model/proposition1.hpp"

namespace lagrange::controller {

config::Scenario suggestGains(const config::Scenario& in) {
  config::Scenario s = in;
  const model::RobotModelPtr arm = s.controlModel();
  const model::Reference reference(s.reference);
  // Without a closed form of C there is only the largest ratio found; the gain
  // report printed after the suggestion says that k_c is then an estimate.
  const std::optional<double> proven_kc = model::coriolisBound(*arm);
  const double kc = proven_kc ? *proven_kc : model::coriolisLargestFound(*arm);
  const double kdelta = model::referenceBound(reference);
  PaperSettings& paper = paperSettings(s);
  Theorem1Gains& g0 = paper.gains;
  const int n = s.dof();
  const int m = static_cast<int>(paper.stages.size());
  if (m == 0) {
    // eq. (11): (kd_min / 2)(b_min / a_max) > k_c k_delta.
    const double kd = 1.1 * 2.0 * kc * kdelta * g0.a.maxCoeff() / g0.b.minCoeff();
    g0.kd = g0.kd.cwiseMax(Eigen::VectorXd::Constant(n, kd));
    return s;
  }
  const double ratio = 8.0 * m;
  g0.a = ratio * g0.b;
  const double half = (m + 2) / 2.0;
  const double kd0 = 1.1 * (half + (kc * kdelta + half) * ratio * ratio) / (ratio / 4.0 - m);
  g0.kd = Eigen::VectorXd::Constant(n, kd0);
  const model::EtaEstimate eta = model::estimateEta(*arm, reference, g0.kp, g0.kd, g0.a, g0.b);
  const double e = eta.eta2 * eta.eta2 + eta.eta3 * eta.eta3;

  // Proposition 1: (794a) kp1 = kd1 with kp1, a1 above (794b), (632b), (632c);
  // for i >= 2, kp_i and a_i above (795b), (795c) by a factor f_i, and kd_i
  // from (795a) read with kd_i^2 (see model/proposition1.hpp), which zeroes
  // every eta_ik. Those bounds do not imply Q - diag(Q)/2 >= 0 ("strengthened
  // if necessary", says the proof). Stage i's rows couple to the earlier ones
  // through mu_ik, which do not depend on stage i's gains, so after scaling by
  // Q's diagonal the couplings fall like 1 / sqrt(f_i): f_i doubles until the
  // first i stages meet the matrix condition with room for the stages after.
  std::vector<double> factors(m, 1.1);
  auto build = [&](int count) {
    std::vector<StageGains> stages(count);
    double kp_prev = 0.0, beta_product = 1.0;
    for (int i = 1; i <= count; ++i) {
      const double b = 1.0, f = factors[i - 1];
      double kp = f * e + 2.0, kd = kp, a = kp;
      if (i > 1) {
        kp = f * (e * beta_product * beta_product + kp_prev);
        kd = std::sqrt(kp * (kp - kp_prev));
        a = f * e * (b * beta_product) * (b * beta_product);
      }
      stages[i - 1] = {Eigen::VectorXd::Constant(n, kp), Eigen::VectorXd::Constant(n, kd),
                       Eigen::VectorXd::Constant(n, a), Eigen::VectorXd::Constant(n, b)};
      beta_product *= kp + b * kd;
      kp_prev = kp;
    }
    return stages;
  };
  auto meets = [&](const std::vector<StageGains>& stages, double matrix_target) {
    std::vector<model::StageVectors> vectors;
    for (const auto& st : stages) vectors.push_back({st.kp, st.kd, st.a, st.b});
    const auto conditions = model::proposition1Conditions(eta, vectors);
    return std::all_of(conditions.begin(), conditions.end(), [](const auto& c) { return c.holds; }) &&
           conditions.back().lhs > matrix_target;
  };
  for (int i = 2; i <= m; ++i)
    while (!meets(build(i), 0.5 + 0.1 * (m - i)) && factors[i - 1] < 1e12) factors[i - 1] *= 2.0;
  paper.stages = build(m);
  for (int i = 1; i <= m; ++i) {
    const StageGains& g = paper.stages[i - 1];
    if (!(g.kp.allFinite() && g.kd.allFinite() && g.a.allFinite()))
      throw std::range_error(
          "Proposition 1's constructive gains for m = " + std::to_string(m) + " overflow " +
          "double precision at stage " + std::to_string(i) +
          " (they grow like e^(3^(i-1)), e = eta_2^2 + eta_3^2); expected m <= " + std::to_string(i - 1) +
          " for this rule, or gains checked against Theorem 3 directly");
  }
  return s;
}

std::string controllerYaml(const config::Scenario& s) {
  const std::string all = config::toYaml(s);
  const auto begin = all.find("controller:");
  const auto end = all.find("\nmetrics:");
  return all.substr(begin, end == std::string::npos ? std::string::npos : end - begin) + "\n";
}

}  // namespace lagrange::controller
