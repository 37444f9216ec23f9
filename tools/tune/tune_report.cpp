#include "tools/tune/tune_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace lagrange::tools {

std::string shortNumber(double v, const char* format) {
  char buf[48];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}
std::string seconds(const std::optional<double>& t) { return t ? shortNumber(*t) + " s" : "none"; }

std::string gainsText(const TuneGains& gains) {
  std::string out;
  for (const auto& [name, values] : gains) {
    out += (out.empty() ? "" : ", ") + name + " ";
    if (values.size() == 1) {
      out += shortNumber(values.front());
      continue;
    }
    out += "[";
    for (size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + shortNumber(values[i]);
    out += "]";
  }
  return out;
}

// What keeps every candidate out, in words (docs/tuning.md, "When nothing
// passes"): the reference's size for eq. (12) with --require-condition,
// the rate, the torque limit, the metric itself.
std::vector<std::string> whatBinds(const TuneProblem& p, const std::vector<TuneEvaluation>& all) {
  std::vector<std::string> out;
  const auto failed = [](const TuneEvaluation& e, const char* prefix) {
    return e.failed.rfind(prefix, 0) == 0;
  };
  const double rate = p.input.plant.publish_rate;
  if (p.require_condition && p.kc && p.kdelta &&
      std::none_of(all.begin(), all.end(),
                   [](const TuneEvaluation& e) { return e.margin && *e.margin > 0.0; })) {
    double lhs = 0.0;
    for (const TuneEvaluation& e : all)
      if (e.condition_lhs) lhs = std::max(lhs, *e.condition_lhs);
    out.push_back(
        "the reference's size: eq. (12), (kd_min / 2)(b_min / a_max) > k_c k_delta, held for none of "
        "the gains tried (k_c = " +
        shortNumber(*p.kc) + ", k_delta = " + shortNumber(*p.kdelta) + "); the largest left side found, " +
        shortNumber(lhs) +
        ", would satisfy it for a reference with "
        "k_delta < " +
        shortNumber(lhs / *p.kc) + " (or the gains' range, --span, is too narrow)");
  }
  // The rate: loops that met the metric within the torque limit, judged not adequate when sampled.
  const TuneEvaluation* fastest = nullptr;
  for (const TuneEvaluation& e : all)
    if (failed(e, "sampled") && e.convergence_time &&
        (!fastest || *e.convergence_time < *fastest->convergence_time))
      fastest = &e;
  if (fastest) {
    std::string text = "the rate: the fastest loop found (" + gainsText(fastest->gains) + ") converged at " +
                       seconds(fastest->convergence_time) +
                       " from the initial state, but the sampled-data "
                       "check at " +
                       shortNumber(rate) + " Hz says " + fastest->sampled_verdict;
    if (fastest->sufficient_rate)
      text += "; the linearised check says " + shortNumber(*fastest->sufficient_rate) + " Hz would suffice";
    else if (!fastest->linearised_verdict.empty())
      text +=
          " (the linearised check says " + fastest->linearised_verdict + " at " + shortNumber(rate) + " Hz)";
    out.push_back(text);
  }
  const TuneEvaluation* lightest = nullptr;
  for (const TuneEvaluation& e : all)
    if (failed(e, "torque") && (!lightest || e.peak_torque < lightest->peak_torque)) lightest = &e;
  if (lightest && !fastest)
    out.push_back("the torque limit: every loop that met the metric needed more than " +
                  shortNumber(p.torque_limit) + " N m (" +
                  (p.torque_from_saturation ? "actuator.saturation" : "the input gains' peak") +
                  "); the least found was " + shortNumber(lightest->peak_torque) + " N m (" +
                  gainsText(lightest->gains) + ")");
  // (Candidates eq. (12) kept out with --require-condition were never run.)
  const bool any_run =
      std::any_of(all.begin(), all.end(), [](const TuneEvaluation& e) { return !e.status.empty(); });
  if (!fastest && !lightest && any_run) {
    // Nothing met the metric from the initial state: the closest, and what
    // the linearised check says of the rate at its gains.
    const TuneEvaluation* closest = nullptr;
    for (const TuneEvaluation& e : all)
      if (!e.status.empty() && std::isfinite(e.final_error) &&
          (!closest || e.final_error < closest->final_error))
        closest = &e;
    std::string text = "the metric: no gains run met it from the initial state (||q~|| below " +
                       shortNumber(p.input.metrics.tolerance) + " rad by " +
                       shortNumber(p.input.metrics.convergence_deadline) + " s)";
    if (closest) {
      text += "; the closest (" + gainsText(closest->gains) + ") ended " + shortNumber(closest->final_error) +
              " rad off";
    }
    // The rate, as the linearised check sees it at the input's gains (the
    // search's start: the gains the user chose).
    try {
      const controller::SampledDataCheck lin = linearisedCheckOf(p, all.front().gains);
      text += "; at the input gains the linearised check says " + lin.verdict + " at the rate, " +
              shortNumber(rate) + " Hz";
      if (lin.sufficient_rate)
        text += ", and that " + shortNumber(*lin.sufficient_rate) + " Hz would suffice";
    } catch (const std::exception&) {
    }
    out.push_back(text);
  }
  return out;
}

nlohmann::ordered_json side(const TuneEvaluation& e) {
  nlohmann::ordered_json j;
  nlohmann::ordered_json gains = nlohmann::ordered_json::object();
  for (const auto& [name, values] : e.gains) gains[name] = values;
  j["gains"] = gains;
  j["convergence_time"] = e.convergence_time ? nlohmann::json(*e.convergence_time) : nlohmann::json();
  j["peak_torque"] = std::isfinite(e.peak_torque) ? nlohmann::json(e.peak_torque) : nlohmann::json();
  j["margin"] = e.margin ? nlohmann::json(*e.margin) : nlohmann::json();
  j["sampled_verdict"] = e.sampled_verdict.empty() ? nlohmann::json() : nlohmann::json(e.sampled_verdict);
  j["feasible"] = e.feasible ? nlohmann::json(*e.feasible) : nlohmann::json();
  j["failed"] = e.failed.empty() ? nlohmann::json() : nlohmann::json(e.failed);
  return j;
}

void printSummary(const TuneEvaluation& input, const TuneEvaluation& best, const TuneProblem& p) {
  const auto row = [](const std::string& what, const std::string& a, const std::string& b) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "  %-22s %-16s %s\n", what.c_str(), a.c_str(), b.c_str());
    std::cout << buf;
  };
  const auto margin = [](const TuneEvaluation& e) {
    return e.margin ? shortNumber(*e.margin) + (*e.margin > 0.0 ? " (holds)" : " (fails)") : "not known";
  };
  const auto verdict = [](const TuneEvaluation& e) {
    return e.sampled_verdict.empty() ? std::string("not run") : e.sampled_verdict;
  };
  row("", "input", "tuned");
  row("convergence time", seconds(input.convergence_time), seconds(best.convergence_time));
  row("peak |torque|", shortNumber(input.peak_torque) + " N m", shortNumber(best.peak_torque) + " N m");
  if (p.kc) row("eq. (12) margin", margin(input), margin(best));
  row("sampled-data check", verdict(input), verdict(best));
  std::cout << "  input gains: " << gainsText(input.gains) << "\n  tuned gains: " << gainsText(best.gains)
            << "\n";
}

}  // namespace lagrange::tools
