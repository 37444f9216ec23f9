#include "controller/gain_suggestion.hpp"

#include <cmath>
#include <sstream>

#include "model/bounds.hpp"
#include "model/chain_conditions.hpp"

namespace lagrange::controller {

config::Scenario suggestGains(const config::Scenario& in) {
  config::Scenario s = in;
  const model::PlanarChain chain(s.robot);
  const model::Reference reference(s.reference);
  const double kc = model::coriolisBound(chain), kdelta = model::referenceBound(reference);
  Theorem1Gains& g0 = s.controller.gains;
  const int n = s.dof();
  const int m = s.actuator.order;
  if (s.controller.type != "cascaded") {
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
  const model::EtaEstimate eta = model::estimateEta(chain, reference, g0.kp, g0.kd, g0.a, g0.b);
  const double e = eta.eta2 * eta.eta2 + eta.eta3 * eta.eta3;

  s.controller.stages.assign(m, StageGains{});
  double kp_prev = 0.0, beta_product = 1.0;
  for (int i = 1; i <= m; ++i) {
    double kp = 0.0, kd = 0.0, a = 0.0;
    const double b = 1.0;
    if (i == 1) {
      kp = kd = a = 1.1 * e + 2.0;
    } else {
      kp = 1.1 * (e * beta_product * beta_product + kp_prev);
      kd = kp * (kp - kp_prev);
      a = 1.1 * e * (b * beta_product) * (b * beta_product);
    }
    s.controller.stages[i - 1] = {Eigen::VectorXd::Constant(n, kp), Eigen::VectorXd::Constant(n, kd),
                                  Eigen::VectorXd::Constant(n, a), Eigen::VectorXd::Constant(n, b)};
    beta_product *= kp + b * kd;
    kp_prev = kp;
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
