#include "controller/gain_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "controller/paper_section.hpp"
#include "model/bounds.hpp"
#include "model/proposition1.hpp"
#include "model/theorem3.hpp"

namespace lagrange::controller {

bool GainReport::holds() const {
  return !unchecked && condition.holds &&
         std::all_of(chain.begin(), chain.end(), [](const auto& c) { return c.holds; });
}

bool GainReport::propositionHolds() const {
  return !proposition.empty() &&
         std::all_of(proposition.begin(), proposition.end(), [](const auto& c) { return c.holds; });
}

double GainReport::margin() const {
  double m = condition.margin();
  for (const auto& c : chain) m = std::min(m, c.margin());
  return m;
}

const model::ConditionReport& GainReport::binding() const {
  std::vector<const model::ConditionReport*> all{&condition};
  for (const auto& c : chain) all.push_back(&c);
  const bool violated = !holds();
  const model::ConditionReport* best = nullptr;
  for (const model::ConditionReport* c : all) {
    if (violated && c->holds) continue;
    // A margin that is not a number binds only when nothing else is left.
    if (!best || c->margin() < best->margin() || std::isnan(best->margin())) best = c;
  }
  return best ? *best : condition;
}

GainReport checkPaperGains(const config::Scenario& s, bool sampled_data) {
  GainReport r;
  // For flexible joints the links as the chain (600) sees them: g(q1) + K q1.
  const model::RobotModelPtr arm = s.controlModel();
  const model::Reference reference(s.reference);
  const std::optional<double> proven_kc = model::coriolisBound(*arm);
  r.kc_found = model::coriolisLargestFound(*arm);
  r.kc_proven = proven_kc.has_value();
  r.kc = proven_kc ? *proven_kc : r.kc_found;
  r.kdelta = model::referenceBound(reference);
  r.kdelta_exact = reference.boundIsExact();
  const PaperSettings& paper = paperSettings(s);
  const Theorem1Gains& g0 = paper.gains;
  r.condition = model::theorem1Condition(g0.kd, g0.a, g0.b, r.kc, r.kdelta);
  if (s.controller.type == "cascaded" || s.controller.type == "flexible") {
    // Only free_motion solves D(q_d) q_d'' + C(q_d, q_d') q_d' + g(q_d) = 0
    // (for flexible joints with g + K q: eq. 608).
    if (s.reference.type != model::ReferenceType::kFreeMotion)
      r.warnings.push_back(
          "the reference (" + std::string(model::toString(s.reference.type)) +
          ") is not a free motion of the " + (s.flexible ? "arm with its springs (eq. (46))" : "arm") +
          ": Assumption 2, a hypothesis of Theorems 5 and 6" + (s.flexible ? " and Corollary 3" : "") +
          ", does not hold, so their guarantee does not apply to this run");
    if (s.controller.type == "flexible" && paper.motor_rate == MotorRate::kFiltered)
      r.warnings.push_back(
          "motor_rate: filtered estimates q2' by a dirty derivative; Corollary 3 assumes xi_2 = K q2' "
          "is measured, so its guarantee does not cover this controller");
    r.eta = model::estimateEta(*arm, reference, g0.kp, g0.kd, g0.a, g0.b);
    if (paper.stages.size() == 1) {
      const StageGains& g1 = paper.stages.at(0);
      r.chain = model::theorem2Conditions(r.kc, r.kdelta, *r.eta, g0.kd, g0.a, g0.b, g1.kp, g1.a, g1.b);
    } else {
      std::vector<model::StageVectors> stages;
      for (const auto& st : paper.stages) stages.push_back({st.kp, st.kd, st.a, st.b});
      r.chain = model::theorem3Conditions(r.kc, r.kdelta, *r.eta, g0.kd, g0.a, g0.b, stages);
      const StageGains& g1 = paper.stages.at(0);
      r.proposition = model::theorem2Conditions(r.kc, r.kdelta, *r.eta, g0.kd, g0.a, g0.b, g1.kp, g1.a, g1.b);
      for (auto& c : model::proposition1Conditions(*r.eta, stages)) r.proposition.push_back(std::move(c));
    }
  }
  if (sampled_data) r.sampled = checkSampledData(s);
  return r;
}

namespace {
std::string line(const model::ConditionReport& c) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "gain condition %s %s: %s  [%.6g > %.6g, margin %.6g]", c.name.c_str(),
                c.holds ? "HOLDS" : "VIOLATED", c.expression.c_str(), c.lhs, c.rhs, c.margin());
  return buf;
}
}  // namespace

std::string describe(const GainReport& r) {
  if (r.unchecked) return "gain conditions NOT CHECKED: " + *r.unchecked;
  char kc[256];
  if (r.kc_proven)
    std::snprintf(
        kc, sizeof kc,
        "k_c = %.6g (proven bound from the closed-form Christoffel symbols; largest ratio found %.6g)", r.kc,
        r.kc_found);
  else
    std::snprintf(kc, sizeof kc,
                  "k_c = %.6g (estimate: the largest ratio found; this robot model has no closed form of C "
                  "to prove a bound from)",
                  r.kc);
  char kdelta[128];
  std::snprintf(kdelta, sizeof kdelta, "k_delta = %.6g (%s)", r.kdelta,
                r.kdelta_exact ? "closed form" : "estimate: sampled supremum x 1.02");
  std::string out = line(r.condition) + "  [" + kc + ", " + kdelta + "]";
  if (!r.kc_proven || !r.kdelta_exact)
    out += std::string("\n  (eq. (12)'s verdict rests on the estimated ") +
           (!r.kc_proven && !r.kdelta_exact ? "k_c and k_delta"
            : !r.kc_proven                  ? "k_c"
                                            : "k_delta") +
           ")";
  if (r.eta) {
    char eta[320];
    std::snprintf(eta, sizeof eta,
                  "\nestimated eta_1 = %.6g, eta_2 = %.6g (sampled suprema refined by local ascent, x 1.1), "
                  "eta_3 = %.6g (exact) (bound (54)); the verdicts below rest on these estimates",
                  r.eta->eta1, r.eta->eta2, r.eta->eta3);
    out += eta;
  }
  for (const auto& c : r.chain) out += "\n" + line(c);
  if (!r.proposition.empty()) {
    out += std::string("\nProposition 1 (constructive, sufficient for Theorem 6) ") +
           (r.propositionHolds() ? "HOLDS:" : "does not hold:");
    for (const auto& c : r.proposition) out += "\n  " + line(c);
  }
  for (const auto& w : r.warnings) out += "\nwarning: " + w;
  if (r.simulated) out += "\n" + describe(*r.simulated);
  if (!r.sampled.verdict.empty()) out += "\n" + describe(r.sampled);
  return out;
}

}  // namespace lagrange::controller
