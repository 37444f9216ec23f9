#include "controller/gain_report.hpp"

#include <cstdio>

#include "model/bounds.hpp"

namespace lagrange::controller {

GainReport checkGains(const config::Scenario& s) {
  GainReport r;
  r.kc = model::coriolisBound(model::PlanarChain(s.robot));
  r.kdelta = model::referenceBound(model::Reference(s.reference));
  r.condition = model::theorem1Condition(s.controller.gains.kd, s.controller.gains.a, s.controller.gains.b,
                                         r.kc, r.kdelta);
  if (s.controller.type == "cascaded")
    r.condition.name += ", stage 0 only (the conditions of Theorems 2 and 3 are not evaluated by this version)";
  return r;
}

std::string describe(const GainReport& r) {
  char line[768];
  std::snprintf(
      line, sizeof line, "gain condition %s %s: %s  [%.6g > %.6g, margin %.6g; k_c = %.6g, k_delta = %.6g]",
      r.condition.name.c_str(), r.condition.holds ? "HOLDS" : "VIOLATED", r.condition.expression.c_str(),
      r.condition.lhs, r.condition.rhs, r.condition.margin(), r.kc, r.kdelta);
  return line;
}

}  // namespace lagrange::controller
