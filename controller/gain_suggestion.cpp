#include "controller/gain_suggestion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "controller/paper_section.hpp"
#include "controller/sampled_data.hpp"
#include "model/bounds.hpp"
#include "model/chain_conditions.hpp"
#include "model/proposition1.hpp"
#include "model/reference.hpp"

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
          " for this rule, or gains checked against Theorem 6 directly");
  }
  return s;
}

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// The search's linearisation of a candidate. The map is the nominal lossless
// model's (controller/sampled_data.hpp) and judges nothing on a plant with
// damping, friction, stops, a payload or model error; the search then
// linearises the nominal plant -- the gains' effect on sampling is the same
// -- and the simulated check judges the real one.
SampledDataCheck linearise(config::Scenario candidate) {
  config::PlantConfig& p = candidate.plant;
  p.joint_damping.reset();
  p.joint_friction.reset();
  p.rotor_damping.reset();
  p.rotor_friction.reset();
  p.urdf_dynamics = false;
  p.joint_limits = false;
  p.payload.reset();
  p.model_error.reset();
  return checkSampledData(candidate);
}

// Whether the reference alone needs more torque than actuator.saturation
// allows somewhere in the run: D(q_d) q_d'' + C(q_d, q_d') q_d' + g(q_d), the
// torque at zero error, against each joint's limit. Then no gains track it.
std::optional<std::string> torqueLimitBinding(const config::Scenario& s, const model::RobotModel& arm,
                                              const model::Reference& reference) {
  if (!s.actuator.saturation || s.flexible) return std::nullopt;
  const Eigen::VectorXd& limit = *s.actuator.saturation;
  constexpr int kSamples = 1000;
  for (int k = 0; k <= kSamples; ++k) {
    const double t = s.duration * k / kSamples;
    const model::ReferenceSample d = reference.evaluate(t, 2);
    const Eigen::VectorXd tau = arm.inverseDynamics(d.q(), d.qd(), d.qdd());
    for (int j = 0; j < s.dof(); ++j)
      if (std::abs(tau(j)) > limit(j))
        return "the torque limits: the reference alone needs " + number(std::abs(tau(j))) + " N m on joint " +
               std::to_string(j + 1) + " at t = " + number(t) +
               " s (D(q_d) q_d'' + C q_d' + g(q_d)), above its " + "limit " + number(limit(j)) +
               " N m (actuator.saturation); no gains track it -- raise the limit " + "or slow the reference";
  }
  return std::nullopt;
}

std::string describeGains(const Theorem1Gains& g) {
  return "kd_min " + number(g.kd.minCoeff()) + ", a_max " + number(g.a.maxCoeff()) + ", b_min " +
         number(g.b.minCoeff()) + ", kp_max " + number(g.kp.maxCoeff());
}

// Theorem 1's search (gain_suggestion.hpp).
GainSearch searchTheorem1(const config::Scenario& in) {
  GainSearch out;
  const model::RobotModelPtr arm = in.controlModel();
  const model::Reference reference(in.reference);
  const std::optional<double> proven_kc = model::coriolisBound(*arm);
  const double kc = proven_kc ? *proven_kc : model::coriolisLargestFound(*arm);
  out.kdelta = model::referenceBound(reference);
  const double rate = in.plant.publish_rate;
  if (auto torque = torqueLimitBinding(in, *arm, reference)) {
    out.binding = *torque;
    return out;
  }
  const Theorem1Gains base = paperSettings(in).gains;
  // eq. (11) with 10 % margin; the filter's scaling leaves b_min / a_max as it is.
  const double kd_need = 1.1 * 2.0 * kc * out.kdelta * base.a.maxCoeff() / base.b.minCoeff();
  auto candidate = [&](double filter, double kp_factor, double kd_floor) {
    config::Scenario c = in;
    Theorem1Gains& g = paperSettings(c).gains;
    g.a = filter * base.a;
    g.b = filter * base.b;
    g.kd = base.kd.cwiseMax(Eigen::VectorXd::Constant(in.dof(), kd_floor));
    g.kp = kp_factor * base.kp;
    return c;
  };
  // Closest to the configured gains first: the filter as it is, then slower
  // (what a light joint at a low rate needs), then faster.
  const std::vector<double> filters = {1.0,      0.5,       0.25,      0.125, 1.0 / 16, 1.0 / 32,
                                       1.0 / 64, 1.0 / 128, 1.0 / 256, 2.0,   4.0,      8.0};
  std::optional<config::Scenario> slow;
  SampledDataCheck slow_check;
  std::optional<double> best_rate;
  std::string best_rate_gains;
  for (const double kp_factor : {1.0, 0.5, 0.25}) {
    for (const double filter : filters) {
      const config::Scenario c = candidate(filter, kp_factor, kd_need);
      const SampledDataCheck check = linearise(c);
      const Theorem1Gains& g = paperSettings(c).gains;
      out.tried.push_back(describeGains(g) + ": " + check.verdict);
      out.linearised = check;
      if (check.adequate()) {
        out.suggested = c;
        return out;
      }
      if (check.verdict == "slow" && !slow) {
        slow = c;
        slow_check = check;
      }
      if (check.sufficient_rate && (!best_rate || *check.sufficient_rate < *best_rate)) {
        best_rate = check.sufficient_rate;
        best_rate_gains = describeGains(g);
      }
    }
    if (slow) {  // not as fast as the continuous loop, but stable at the rate: better than lower kp
      out.suggested = slow;
      out.linearised = slow_check;
      return out;
    }
  }
  if (out.linearised.verdict == "not assessed") {
    out.binding = "the linearised check cannot judge these candidates (" + out.linearised.why + ")";
    return out;
  }

  // None keeps eq. (11) and is stable at the rate. What eq. (11) would allow
  // with gains the rate does: kd (eq. (11)'s, or the configured where higher)
  // lowered by halves on every joint, with each filter tried above, until
  // the linearised loop is adequate or slow; the largest k_delta such gains
  // meet eq. (11) for.
  for (const double filter : filters) {
    for (int k = 1; k <= 12; ++k) {
      config::Scenario c = candidate(filter, 1.0, kd_need);
      Theorem1Gains& g = paperSettings(c).gains;
      g.kd *= std::pow(0.5, k);
      const std::string verdict = linearise(c).verdict;
      if (verdict != "adequate" && verdict != "slow") continue;
      const double allowed = g.kd.minCoeff() * g.b.minCoeff() / (2.0 * g.a.maxCoeff() * kc);
      if (!out.kdelta_allowed || allowed > *out.kdelta_allowed) out.kdelta_allowed = allowed;
      break;
    }
  }
  out.sufficient_rate = best_rate;
  std::string binding =
      "eq. (12) against the rate: eq. (12) asks kd_min b_min / a_max > 2 k_c k_delta = " +
      number(2.0 * kc * out.kdelta) + " (k_c " + number(kc) + ", k_delta " + number(out.kdelta) +
      "), and no candidate that keeps it (kd at least " + number(kd_need) +
      " on every joint, the filter a, b scaled by 1/256 to 8, kp by 1 to 1/4; " +
      std::to_string(out.tried.size()) + " tried) is adequate or slow in the linearised check at " +
      number(rate) + " Hz: each is unstable, or too slow for the check to assess. ";
  binding += best_rate ? "The rate binds: " + number(*best_rate) +
                             " Hz would suffice (plant.publish_rate) for " + best_rate_gains + ". "
                       : "No rate up to 1024 x this one makes such a candidate adequate. ";
  binding += out.kdelta_allowed
                 ? "The reference's size binds through k_delta: gains stable at " + number(rate) +
                       " Hz meet eq. (12) only for k_delta < " + number(*out.kdelta_allowed) +
                       ", and this reference's is " + number(out.kdelta) +
                       " (a smaller or slower reference: reference.offset, amplitude, frequency)"
                 : "No gains tried are stable at " + number(rate) + " Hz even without eq. (12)";
  out.binding = binding;
  return out;
}

}  // namespace

GainSearch searchGains(const config::Scenario& s) {
  // Held for the search: every candidate's linearisation builds the
  // reference again, and a free_motion one is then integrated once (model/reference.hpp).
  const model::Reference reference(s.reference);
  const PaperSettings& paper = paperSettings(s);
  if (s.controller.type == "theorem1") return searchTheorem1(s);
  GainSearch out;
  out.kdelta = model::referenceBound(reference);
  if (s.controller.type != "cascaded" || paper.stages.empty()) {
    out.binding =
        "--suggest searches the gains of controller.type theorem1 and cascaded; this is " + s.controller.type;
    return out;
  }
  // The chains: Proposition 1's constructive rules, then the rate.
  const config::Scenario c = suggestGains(s);
  out.linearised = checkSampledData(c);
  out.tried.push_back("Proposition 1's constructive gains: " + out.linearised.verdict);
  if (out.linearised.verdict == "adequate" || out.linearised.verdict == "slow") {
    out.suggested = c;
    return out;
  }
  out.sufficient_rate = out.linearised.sufficient_rate;
  out.binding = "the rate: the constructive gains of Proposition 1 (stage gains up to " +
                number(paperSettings(c).stages.back().kp.maxCoeff()) + ") are " + out.linearised.verdict +
                " in the linearised check at " + number(s.plant.publish_rate) + " Hz" +
                (out.linearised.sufficient_rate ? "; " + number(*out.linearised.sufficient_rate) +
                                                      " Hz would suffice (plant.publish_rate)"
                 : out.linearised.verdict == "not assessed" ? " (" + out.linearised.why + ")"
                                                            : "; no rate up to 1024 x this one suffices");
  return out;
}

std::string controllerYaml(const config::Scenario& s) {
  const std::string all = config::toYaml(s);
  const auto begin = all.find("controller:");
  const auto end = all.find("\nmetrics:");
  return all.substr(begin, end == std::string::npos ? std::string::npos : end - begin) + "\n";
}

}  // namespace lagrange::controller
