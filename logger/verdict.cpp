#include "logger/verdict.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "util/terminal_text.hpp"

namespace lagrange::logger {

namespace {

using nlohmann::json;

// A field by JSON pointer, or null when any part is missing: a summary of an
// older version, or of a run that never reached a part, still gets a verdict.
const json& at(const json& j, const char* pointer) {
  static const json none;
  const json::json_pointer p(pointer);
  return j.is_object() && j.contains(p) ? j.at(p) : none;
}

double number(const json& v, double otherwise = std::nan("")) {
  return v.is_number() ? v.get<double>() : otherwise;
}

long long count(const json& v) { return v.is_number() ? v.get<long long>() : 0; }

// Strings come from the run's files and programs (a process's last line, an
// external program's command): printed on terminals, so made safe to print.
std::string text(const json& v) {
  return v.is_string() ? util::terminalSafe(v.get<std::string>()) : std::string();
}

// 3 significant figures, but whole numbers from 1000 on (a rate reads
// "3200 Hz", not "3.2e+03 Hz").
std::string g(double v) {
  return std::abs(v) >= 1000.0 && std::abs(v) < 1e9 ? fmt::format("{:.0f}", v) : fmt::format("{:.3g}", v);
}

// Truncated, never rounded up: 98.999 % stays below a 99 % threshold in print too.
std::string percent(double fraction) {
  const double p = std::floor(100.0 * fraction * 1000.0 + 1e-6) / 1000.0;  // 0.03 % is not 0.029 %
  if (p == 0.0 && fraction > 0.0) return "< 0.001 %";
  return fmt::format("{:g} %", p);
}

struct Finding {
  std::string kind, text;
};

class Verdict {
 public:
  Verdict(const json& summary, const VerdictThresholds& limits) : s_(summary), limits_(limits) {}

  json decide() {
    const std::string status = text(at(s_, "/status"));
    judged_ = status == "completed" || status == "failed" || status == "diverged";
    const bool met = status == "completed" && at(s_, "/tracking/met") == true && !truthMissing();
    met_ = met;
    processFailed();
    missingTruth();
    diverged();
    samplingRate();
    timing();
    saturated();
    condition();
    notConverged();
    otherWarnings();
    json out;
    out["tracking"] = met ? "met" : judged_ ? "NOT met" : "not judged";
    out["met"] = met;
    out["headline"] = headline(status);
    out["reasons"] = asJson(reasons_);
    out["warnings"] = asJson(warnings_);
    return out;
  }

 private:
  const json& s_;
  VerdictThresholds limits_;
  bool judged_ = false, met_ = false;
  std::vector<Finding> reasons_, warnings_;

  // A finding is a reason when the metric was missed, else a warning: what
  // explains a miss still deserves a word when the run got away with it.
  void found(const std::string& kind, const std::string& what, bool only_a_warning = false) {
    (met_ || only_a_warning || !judged_ ? warnings_ : reasons_).push_back({kind, what});
  }

  static json asJson(const std::vector<Finding>& findings) {
    json out = json::array();
    for (const Finding& f : findings) out.push_back({{"kind", f.kind}, {"text", f.text}});
    return out;
  }

  std::string headline(const std::string& status) const {
    // Met, but with what matters said: the first line never hides that the
    // run was not what it claims to be (a realtime run far off its rate).
    if (met_)
      return warnings_.empty() ? "tracking met"
                               : fmt::format("tracking met; {} warning{}, the first: {}", warnings_.size(),
                                             warnings_.size() == 1 ? "" : "s", warnings_.front().text);
    if (!judged_) {
      const double t = number(at(s_, "/timing/sim_time"), 0.0);
      return fmt::format("tracking not judged: the run was {} at t = {} s, before its last tick",
                         status.empty() ? "not finished" : status, g(t));
    }
    std::string line = "tracking NOT met";
    for (size_t i = 0; i < reasons_.size() && i < 2; ++i) line += (i == 0 ? ": " : "; ") + reasons_[i].text;
    return line;
  }

  void processFailed() {
    const json& failure = at(s_, "/failure");
    if (!failure.is_object() || failure.value("diverged", false)) return;  // a divergence: diverged()
    const std::string process = text(at(failure, "/process"));
    const std::string how = text(at(failure, "/how"));
    found("process_failed",
          fmt::format("the {} failed{}{}", process.empty() ? "run" : process, how.empty() ? "" : ": ", how),
          text(at(s_, "/status")) == "completed");
  }

  // The plant's samples the log lacks: the metric is of the ticks it holds,
  // so past the threshold it is no metric of the run (a plant that skipped
  // ticks, or a run whose samples were lost on the way).
  long long truthMissingCount() const { return count(at(s_, "/log/missing_ticks/PLANT_TRUTH")); }
  double truthMissingShare() const {
    const long long missing = truthMissingCount(), held = count(at(s_, "/tracking/samples"));
    return missing + held > 0 ? static_cast<double>(missing) / static_cast<double>(missing + held) : 0.0;
  }
  bool truthMissing() const {
    if (truthMissingCount() == 0) return false;
    return text(at(s_, "/mode")) == "lockstep" || truthMissingShare() > limits_.missing_truth_fraction;
  }
  void missingTruth() {
    if (!truthMissing()) return;
    found("missing_ticks",
          fmt::format("the log has no plant sample (PLANT_TRUTH) for {} of the run's ticks ({}): the figures "
                      "are of the ticks it holds, not of the run",
                      truthMissingCount(), percent(truthMissingShare())));
  }

  void diverged() {
    const std::string status = text(at(s_, "/status"));
    const double max_error = number(at(s_, "/tracking/max_error"));
    const double when = number(at(s_, "/tracking/max_error_time"));
    const std::string reached =
        std::isfinite(max_error)
            ? fmt::format("|q~| reached {} rad{}", g(max_error),
                          std::isfinite(when) ? fmt::format(" at t = {} s", g(when)) : std::string())
            : std::string();
    if (status == "diverged") {
      const std::string why = text(at(s_, "/failure/reason"));
      found("diverged", "diverged: the plant stopped the run" + (why.empty() ? "" : " (" + why + ")") +
                            (reached.empty() ? "" : "; " + reached));
      return;
    }
    if (status == "completed" && at(s_, "/failure/diverged") == true) {  // after every tick was recorded
      found("diverged",
            "the plant stopped the simulation after the last tick was recorded (" +
                text(at(s_, "/failure/reason")) + ")",
            true);
      return;
    }
    const double start = number(at(s_, "/tracking/initial_error"));
    const double final_error = number(at(s_, "/tracking/final_error"));
    const double tolerance = number(at(s_, "/tracking/tolerance"), 0.0);
    // Samples whose error is not a number: summary.json writes inf and NaN as null.
    if (count(at(s_, "/tracking/samples")) > 0 &&
        (!std::isfinite(max_error) || !std::isfinite(final_error))) {
      found("diverged", "diverged: the tracking error became infinite or not a number");
      return;
    }
    if (!std::isfinite(max_error) || !std::isfinite(start)) return;
    // Grew and stayed grown: past `growth` times its start (or the tolerance,
    // for a run that starts on its reference) at its largest and at the end.
    // A transient that settles again is no divergence.
    const double bound = limits_.growth * std::max(start, tolerance);
    if (max_error > bound && final_error > bound)
      found("diverged", fmt::format("diverged ({}, from {} rad at the start)", reached, g(start)));
  }

  // The implementation at the run's rate: the linearised check (always
  // there for the paper's controllers) and the simulated one when it ran.
  void samplingRate() {
    const json& sd = at(s_, "/gains/sampled_data");
    const std::string word = text(at(sd, "/verdict"));
    const double rate = number(at(sd, "/rate"));
    const json& enough = at(sd, "/sufficient_rate");
    const std::string suffice =
        enough.is_number() ? fmt::format("; {} Hz would suffice: plant.publish_rate", g(enough.get<double>()))
                           : std::string();
    if (word == "unstable")
      found("unstable_at_rate",
            fmt::format("the sampled loop at {} Hz is unstable (linearised check{})", g(rate), suffice));
    else if (word == "slow")
      found("slow_at_rate",
            fmt::format("the sampled loop at {} Hz converges slower than the continuous one "
                        "(linearised check{})",
                        g(rate), suffice),
            true);
    const json& sim = at(s_, "/gains/sampled_simulation");
    const std::string simulated = text(at(sim, "/verdict"));
    if (!simulated.empty() && simulated != "adequate" && simulated != "not assessed")
      found("sampled_check", fmt::format("the simulated sampled-data check at {} Hz says {}: {}",
                                         g(number(at(sim, "/rate"))), simulated, text(at(sim, "/why"))));
  }

  void timing() {
    // The loop furthest from its rate first.
    std::vector<std::pair<std::string, const json*>> loops;
    if (const json& all = at(s_, "/timing/loops"); all.is_object())
      for (const auto& [name, loop] : all.items()) loops.emplace_back(name, &loop);
    std::stable_sort(loops.begin(), loops.end(), [](const auto& a, const auto& b) {
      return number(at(*a.second, "/on_time_fraction"), 1.0) <
             number(at(*b.second, "/on_time_fraction"), 1.0);
    });
    for (const auto& [name, loop] : loops) {
      const double on_time = number(at(*loop, "/on_time_fraction"), 1.0);
      const long long run = count(at(*loop, "/longest_miss_run"));
      const long long misses = count(at(*loop, "/deadline_misses"));
      const bool fault = on_time < limits_.on_time_fraction || run >= limits_.longest_miss_run;
      if (fault || misses > 0)
        found(
            "timing",
            fmt::format(
                "the {}'s loop was on time on {} of its periods ({} misses, the longest run {} periods{}{})",
                name, percent(on_time), misses, run, slowerThanItsRate(*loop),
                name == "plant" ? freshTorque() : std::string()),
            !fault);
    }
    const json& stale = at(s_, "/messages/stale/plant");
    const long long held = count(at(stale, "/torque_held")), zeroed = count(at(stale, "/torque_zeroed"));
    const long long cycles = count(at(s_, "/timing/loops/plant/cycles"));
    if (held + zeroed > 0) {
      const double share =
          cycles > 0 ? static_cast<double>(held + zeroed) / static_cast<double>(cycles) : 1.0;
      found("stale_torque",
            fmt::format("the plant had no fresh torque on {} periods ({} of {}): held on {}, zeroed on {}",
                        held + zeroed, percent(share), cycles, held, zeroed),
            share <= limits_.stale_torque_fraction);
    }
  }

  // "; it ran at 366 Hz of 1000": a loop that fell behind stretched the
  // run's time (a plant behind schedule slows the whole run).
  static std::string slowerThanItsRate(const json& loop) {
    const double period = number(at(loop, "/period"), 0.0);
    const json& achieved = at(loop, "/achieved_rate");
    if (period <= 0.0 || !achieved.is_number() || achieved.get<double>() >= 0.99 / period) return "";
    return fmt::format("; it ran at {} Hz of {}", g(achieved.get<double>()), g(1.0 / period));
  }

  // A late plant's torque: whether what it applied was fresh, so that the
  // timing reason says it when the stale_torque reason below does not.
  std::string freshTorque() const {
    const json& stale = at(s_, "/messages/stale/plant");
    if (!stale.is_object()) return "";
    const long long held = count(at(stale, "/torque_held")), zeroed = count(at(stale, "/torque_zeroed"));
    return held + zeroed == 0 ? "; its torque was fresh on every period" : "";
  }

  // Neither saturation (which may be by design) nor a violated condition
  // (which the gain line shows) is a warning of a met run.
  void saturated() {
    const double share = number(at(s_, "/torque/saturated_fraction"), 0.0);
    if (share > 0.0 && !met_)
      found(
          "saturated",
          fmt::format("the torque was at its limit (actuator.saturation) on {} of the ticks", percent(share)),
          met_);
  }

  void condition() {
    const json& gains = at(s_, "/gains");
    if (met_ || at(gains, "/checked") != true || at(gains, "/condition_holds") != false) return;
    found("condition_violated",
          fmt::format("{} does not hold (margin {}): the continuous-time guarantee is not given",
                      text(gains.contains("binding_condition") ? at(gains, "/binding_condition")
                                                               : at(gains, "/condition")),
                      g(number(at(gains, "/margin")))),
          met_);
  }

  // The last resort when nothing above explains a miss.
  void notConverged() {
    if (met_ || !judged_ || !reasons_.empty()) return;
    const json& t = at(s_, "/tracking");
    const json& when = at(t, "/convergence_time");
    const double deadline = number(at(t, "/convergence_deadline"));
    if (at(t, "/met") == true) {  // converged in time, but the run did not complete
      reasons_.push_back(
          {"ended_early", fmt::format("the run {} at t = {} s, before its last tick", text(at(s_, "/status")),
                                      g(number(at(s_, "/timing/sim_time"), 0.0)))});
      return;
    }
    // q~ in time, a chain stage not: the stage is what missed.
    if (when.is_number() && when.get<double>() <= deadline) {
      const json& chain = at(t, "/chain");
      if (chain.is_array())
        for (const json& c : chain) {
          const json& stage_time = at(c, "/convergence_time");
          if (stage_time.is_number() && stage_time.get<double>() <= deadline) continue;
          reasons_.push_back(
              {"chain_stage",
               fmt::format("||xit_{}|| (the chain's stage {}) {} (tolerance {}, final {})",
                           count(at(c, "/stage")), count(at(c, "/stage")),
                           stage_time.is_number()
                               ? fmt::format("converged at t = {} s, after the deadline ({} s)",
                                             g(stage_time.get<double>()), g(deadline))
                               : std::string("did not stay below its tolerance"),
                           g(number(at(c, "/tolerance"))), g(number(at(c, "/final_error"))))});
          return;
        }
    }
    if (when.is_number())
      reasons_.push_back({"late", fmt::format("converged at t = {} s, after the deadline ({} s)",
                                              g(when.get<double>()), g(deadline))});
    else
      reasons_.push_back(
          {"not_converged", fmt::format("||q~|| did not stay below {} rad (final {} rad, the last "
                                        "second's RMS {} rad)",
                                        g(number(at(t, "/tolerance"))), g(number(at(t, "/final_error"))),
                                        g(number(at(t, "/rms_last_second"))))});
  }

  void otherWarnings() {
    const json& answers = at(s_, "/answers");
    if (answers.is_object())
      for (const auto& [name, a] : answers.items()) {
        const long long slow = a.is_object() ? count(at(a, "/slow")) : 0;
        if (slow > 0)
          warnings_.push_back(
              {"slow_answers",
               fmt::format("the {} ({}) answered {} tick(s) slower than supervision.slow_answer "
                           "(the worst {} s, at tick {})",
                           name, text(at(a, "/program")), slow, g(number(at(a, "/worst"))),
                           count(at(a, "/worst_tick")))});
      }
    const json& missing = at(s_, "/log/missing_ticks");
    if (missing.is_object())
      for (const auto& [channel, n] : missing.items())
        if (count(n) > 0 && !(channel == "PLANT_TRUTH" && truthMissing()))  // a reason above
          warnings_.push_back({"missing_ticks", fmt::format("the log has no {} for {} ticks: the figures are "
                                                            "of the ticks it holds",
                                                            channel, count(n))});
    const json& restarts = at(s_, "/supervision/restarts");
    if (restarts.is_object())
      for (const auto& [name, n] : restarts.items())
        if (count(n) > 0)
          warnings_.push_back({"restarted", fmt::format("the {} died and was restarted {} time(s) "
                                                        "(supervision.deaths)",
                                                        name, count(n))});
    if (at(s_, "/log/complete") == false)
      warnings_.push_back({"log_incomplete", text(at(s_, "/log/incomplete_because"))});
    const json& crossed = at(s_, "/limits/velocity");
    if (crossed.is_array() && !crossed.empty())
      warnings_.push_back(
          {"velocity_limit", fmt::format("{} joint(s) went past the URDF's velocity limit "
                                         "(limits.velocity): a real drive would fault or clip",
                                         crossed.size())});
  }
};

}  // namespace

nlohmann::json runVerdict(const nlohmann::json& summary, const VerdictThresholds& limits) {
  return Verdict(summary, limits).decide();
}

std::string likeliestReason(const nlohmann::json& verdict) {
  const json& reasons = at(verdict, "/reasons");
  if (reasons.is_array() && !reasons.empty()) return text(at(reasons[0], "/text"));
  const json& warnings = at(verdict, "/warnings");
  if (warnings.is_array() && !warnings.empty()) return "warning: " + text(at(warnings[0], "/text"));
  return "";
}

}  // namespace lagrange::logger
