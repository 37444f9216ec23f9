#include "tools/tune/tune_evaluate.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "controller/gain_report.hpp"
#include "controller/paper_section.hpp"
#include "controller/sampled_data.hpp"
#include "model/gain_conditions.hpp"
#include "util/error.hpp"
#include "wiring/inproc_runner.hpp"
#include "wiring/sampled_simulation.hpp"

namespace lagrange::tools {

namespace {

// A stage's gain is named "stages[i].KEY" (controller.stages[i].KEY).
std::optional<std::pair<size_t, std::string>> stageOf(const std::string& name) {
  const std::string prefix = "stages[";
  const size_t close = name.find("].");
  if (name.rfind(prefix, 0) != 0 || close == std::string::npos) return std::nullopt;
  return std::make_pair(static_cast<size_t>(std::stoul(name.substr(prefix.size(), close - prefix.size()))),
                        name.substr(close + 2));
}

// A gain's values as the resolved scenario holds them (config.resolved.yaml's
// text): the one place that knows every controller's section, so that tune
// reads the paper's section and a baseline's keys alike.
std::vector<double> scenarioGain(const config::Scenario& s, const std::string& name) {
  const YAML::Node controller = YAML::Load(config::toYaml(s))["controller"];
  const auto stage = stageOf(name);
  const YAML::Node node = stage ? controller["stages"][stage->first][stage->second] : controller[name];
  std::vector<double> out;
  if (node.IsSequence())
    for (const YAML::Node& v : node) out.push_back(v.as<double>());
  else if (node.IsScalar())
    out.assign(static_cast<size_t>(s.dof()), node.as<double>());
  return out;
}

std::string exactNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Seconds since t0.
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// x / (1 + x) for x >= 0: a miss squeezed into [0, 1), so that a band's
// penalties stay inside it whatever the miss.
double squeezed(double miss) {
  if (!(miss >= 0.0)) return std::isnan(miss) ? 0.999999 : 0.0;
  if (std::isinf(miss)) return 0.999999;
  return miss / (1.0 + miss);
}

// Added to the cut time for a cut run whose error is not decaying: after
// every run estimated to converge.
constexpr double kNotDecaying = 1e4;

// (k + 1) x period: the time of the sample after tick k's, as the runner computes it.
double nextSampleTime(long long k, double period) { return static_cast<double>(k + 1) * period; }

// Records what judgeCandidate needs of a run's first part (CandidateRun's
// per-tick traces, up to the deadline), and stops the run at the cut.
class CutWatch : public wiring::TickWatch {
 public:
  CutWatch(CandidateRun& run, const config::Scenario& s, const std::atomic<double>* cut)
      : run_(run),
        period_(s.tickPeriod()),
        tolerance_(s.metrics.tolerance),
        record_until_(s.metrics.convergence_deadline),
        cut_(cut) {}
  bool keepGoing(long long tick, double error, const Eigen::MatrixXd& tau) override {
    if (tau.size() > 0) peak_ = std::max(peak_, tau.cwiseAbs().maxCoeff());
    if (static_cast<double>(tick) * period_ <= record_until_) {  // every cut is at or before the deadline
      run_.errors.push_back(error);
      run_.peaks.push_back(peak_);
    }
    return !(cut_ && error >= tolerance_ &&
             nextSampleTime(tick, period_) >= cut_->load(std::memory_order_relaxed));
  }

 private:
  CandidateRun& run_;
  double period_, tolerance_, record_until_;
  const std::atomic<double>* cut_;
  double peak_ = 0.0;
};

// The largest of errors[from..to] (to included).
double largest(const std::vector<double>& errors, size_t from, size_t to) {
  return *std::max_element(errors.begin() + static_cast<long>(from),
                           errors.begin() + static_cast<long>(to) + 1);
}

// A cut run's late error and estimated convergence time: its error
// envelope (the largest ||q~||) over the third and the last quarter of the
// part judged, [X/2, 3X/4) and [3X/4, X]; decaying from one to the next,
// the time at which that exponential decay, from the last quarter's start
// (where a decaying envelope's largest value is), would reach the
// tolerance -- kept after X, the best's time, which it did not beat.
void estimateFromEnvelope(TuneEvaluation& e, const std::vector<double>& errors, size_t last, double cut,
                          double period, double tolerance) {
  const size_t half = std::min(static_cast<size_t>(cutTick(0.5 * cut, period)), last);
  const size_t three_quarters = std::min(static_cast<size_t>(cutTick(0.75 * cut, period)), last);
  e.late_error = largest(errors, three_quarters, last);
  if (half >= three_quarters) return;  // too few ticks judged
  const double before = largest(errors, half, three_quarters - 1);
  if (!(e.late_error < before) || !(e.late_error > 0.0)) return;  // not decaying
  const double per_quarter = std::log(before / e.late_error);
  const double remaining = 0.25 * cut * std::log(std::max(e.late_error, tolerance) / tolerance) / per_quarter;
  e.estimated_time = std::max(0.75 * cut + std::min(remaining, kNotDecaying),
                              std::nextafter(cut, std::numeric_limits<double>::infinity()));
}

}  // namespace

double cutTime(const TuneProblem& p, std::optional<double> best_time) {
  if (!best_time || !(p.cut_factor > 0.0)) return std::numeric_limits<double>::infinity();
  return std::min(p.cut_factor * *best_time, p.input.metrics.convergence_deadline);
}

long long cutTick(double cut, double period) {
  long long k = std::max(0LL, static_cast<long long>(std::ceil(cut / period)) - 1);
  while (k > 0 && nextSampleTime(k - 1, period) >= cut) --k;
  while (nextSampleTime(k, period) < cut) ++k;
  return k;
}

TuneProblem makeTuneProblem(const std::string& scenario_path, const std::vector<std::string>& overrides,
                            double span_decades) {
  TuneProblem p;
  p.scenario_path = scenario_path;
  p.overrides = overrides;
  p.input = config::loadScenario(scenario_path, overrides);
  if (p.input.controller.type == "external")
    throw BadInput(
        "an external controller (controller.type external) is a program lagrange does not know the "
        "gains of; expected a registered controller type: " +
        config::controllerTypeList());
  if (p.input.plant.external())
    throw BadInput(
        "an external plant runs as its own program, and tune simulates in process; expected a "
        "scenario whose plant lagrange simulates");
  // A per-stage gain once for each of the scenario's stages, named
  // "stages[i].KEY": stage 0's gains first, then stage 1's, and so on.
  const std::vector<controller::TunableGain>& declared = controller::tunableGains(p.input.controller.type);
  const YAML::Node stages = YAML::Load(config::toYaml(p.input))["controller"]["stages"];
  const size_t stage_count = stages.IsSequence() ? stages.size() : 0;
  for (const controller::TunableGain& g : declared)
    if (!g.per_stage) p.tunable.push_back(g);
  for (size_t i = 0; i < stage_count; ++i)
    for (controller::TunableGain g : declared)
      if (g.per_stage) {
        g.name = "stages[" + std::to_string(i) + "]." + g.name;
        g.per_stage = false;
        p.tunable.push_back(g);
      }
  const double span = std::pow(10.0, span_decades);
  for (const controller::TunableGain& g : p.tunable) {
    std::vector<double> values = scenarioGain(p.input, g.name);
    if (values.empty()) values.assign(static_cast<size_t>(p.input.dof()), g.fallback);
    if (!g.per_joint) values = {*std::max_element(values.begin(), values.end())};
    for (size_t i = 0; i < values.size(); ++i) {
      const double v = values[i] >= g.lower && values[i] <= g.upper ? values[i] : g.fallback;
      values[i] = v;
      const std::string label = g.per_joint ? g.name + "[" + std::to_string(i) + "]" : g.name;
      p.variables.push_back({label, std::max(g.lower, v / span), std::min(g.upper, v * span), v});
    }
    p.input_gains.emplace_back(g.name, values);
  }
  const controller::GainReport report = controller::checkGains(p.input, /*sampled_data=*/false);
  if (controller::isPaperType(p.input.controller.type) && !report.unchecked) {
    p.kc = report.kc;
    p.kdelta = report.kdelta;
  }
  if (p.input.actuator.saturation && p.input.actuator.saturation->size() > 0) {
    p.torque_limit = p.input.actuator.saturation->maxCoeff();
    p.torque_from_saturation = true;
  }
  return p;
}

TuneGains gainsOf(const TuneProblem& p, const std::vector<double>& point) {
  TuneGains out;
  size_t k = 0;
  for (const controller::TunableGain& g : p.tunable) {
    const size_t n = g.per_joint ? static_cast<size_t>(p.input.dof()) : 1;
    out.emplace_back(g.name, std::vector<double>(point.begin() + static_cast<long>(k),
                                                 point.begin() + static_cast<long>(k + n)));
    k += n;
  }
  return out;
}

std::string stagesYaml(const config::Scenario& input, const TuneGains& gains) {
  YAML::Node stages = YAML::Clone(YAML::Load(config::toYaml(input))["controller"]["stages"]);
  bool tuned = false;
  for (const auto& [name, values] : gains) {
    const auto stage = stageOf(name);
    if (!stage) continue;
    if (!stages.IsSequence() || stage->first >= stages.size())
      throw std::invalid_argument("the gain " + name + " names a stage the scenario does not have");
    YAML::Node list(YAML::NodeType::Sequence);
    for (double v : values) list.push_back(exactNumber(v));  // a plain scalar: read back as the same double
    YAML::Node entry = stages[stage->first];
    entry[stage->second] = values.size() == 1 ? YAML::Node(exactNumber(values.front())) : list;
    tuned = true;
  }
  if (!tuned) return "";
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << stages;
  return out.c_str();
}

std::vector<std::string> gainOverrides(const config::Scenario& input, const TuneGains& gains) {
  std::vector<std::string> out;
  if (const std::string stages = stagesYaml(input, gains); !stages.empty())
    out.push_back("controller.stages=" + stages);
  for (const auto& [name, values] : gains) {
    if (stageOf(name)) continue;  // in controller.stages above
    std::string text = "controller." + name + "=";
    if (values.size() == 1) {
      text += exactNumber(values.front());  // one number for every joint
    } else {
      text += "[";
      for (size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + exactNumber(values[i]);
      text += "]";
    }
    out.push_back(text);
  }
  return out;
}

double tuneValue(const TuneEvaluation& e, const config::Scenario& s, double torque_limit) {
  const double tolerance = s.metrics.tolerance, deadline = s.metrics.convergence_deadline;
  if (e.failed.empty() && e.judged_to)
    return e.estimated_time ? *e.estimated_time
                            : *e.judged_to + kNotDecaying + squeezed(e.late_error / tolerance);
  if (e.failed.empty()) return e.convergence_time.value_or(0.0);
  if (e.failed.rfind("scenario", 0) == 0) return 5e6;
  if (e.failed.rfind("condition", 0) == 0)
    return 4e6 + 1e6 * squeezed(e.margin ? -*e.margin / std::max(1e-12, *e.condition_lhs - *e.margin) : 1.0);
  if (e.failed.rfind("diverged", 0) == 0) return 3e6 + 1e6 * squeezed(e.final_error / tolerance);
  if (e.failed.rfind("metric", 0) == 0) {
    // Late: by how much; never below the tolerance: by how far above it it ends.
    const double miss = e.convergence_time ? (*e.convergence_time - deadline) / deadline
                                           : 1.0 + std::log10(std::max(1.0, e.final_error / tolerance));
    return 2e6 + 1e6 * squeezed(miss);
  }
  if (e.failed.rfind("torque", 0) == 0) return 1e6 + 1e6 * squeezed(e.peak_torque / torque_limit - 1.0);
  // The sampled-data check: by how bad its word, then by how many starts missed the metric.
  const auto& words = controller::SampledSimulation::kVerdicts;
  const auto word =
      std::find_if(std::begin(words), std::end(words), [&](const char* w) { return e.sampled_verdict == w; });
  const long missed = std::count_if(e.start_times.begin(), e.start_times.end(),
                                    [&](const std::optional<double>& t) { return !t || *t > deadline; });
  return 1e5 +
         1e5 * squeezed(static_cast<double>(word - std::begin(words)) + 0.1 * static_cast<double>(missed));
}

CandidateRun runCandidate(const TuneProblem& p, const TuneGains& gains, bool (*stop_requested)(),
                          const std::atomic<double>* cut_time) {
  const auto load_start = std::chrono::steady_clock::now();
  CandidateRun out;
  TuneEvaluation& e = out.findings;
  e.gains = gains;
  std::vector<std::string> overrides = p.overrides;
  for (const std::string& o : gainOverrides(p.input, gains)) overrides.push_back(o);
  try {
    out.scenario = config::loadScenario(p.scenario_path, overrides);
  } catch (const std::exception& error) {
    out.scenario = p.input;
    e.feasible = false;
    e.failed = std::string("scenario refused: ") + error.what();
    return out;
  }
  e.load_time = since(load_start);
  const config::Scenario& s = out.scenario;

  // eq. (11) (printed (12)) with k_c and k_delta of the problem: cheap, so first.
  if (p.kc && p.kdelta) {
    const controller::Theorem1Gains& g0 = controller::paperSettings(s).gains;
    const model::ConditionReport c = model::theorem1Condition(g0.kd, g0.a, g0.b, *p.kc, *p.kdelta);
    e.margin = c.margin();
    e.condition_lhs = c.lhs;
    if (p.require_condition && !c.holds) {
      e.feasible = false;
      e.failed = "condition eq. (12) violated (--require-condition)";
      return out;
    }
  }

  // The run in process; the sampled-data check examines the scenario's own
  // wiring (a realtime scenario with its period of delay).
  config::Scenario in_process = s;
  in_process.mode = config::Mode::kInproc;
  const auto run_start = std::chrono::steady_clock::now();
  CutWatch watch(out, s, cut_time);
  const wiring::InProcessOutcome run = wiring::simulateInProcess(in_process, nullptr, nullptr, stop_requested,
                                                                 p.cut_factor > 0.0 ? &watch : nullptr);
  e.run_time = since(run_start);
  out.interrupted = run.status == "interrupted";
  e.status = run.status;
  // A cut run's convergence time is not known (its summary would put it at the cut).
  if (run.status != "cut") e.convergence_time = run.tracking.convergence_time;
  e.final_error = run.tracking.final_error;
  e.peak_torque = run.tracking.max_abs_torque;
  if (run.status == "diverged")
    e.failed = "diverged from the initial state" + (run.stop_message.empty() ? "" : ": " + run.stop_message);
  // As the check's simulation of the same loop would read it (wiring/sampled_simulation.cpp).
  if (run.status == "completed")
    out.loop = wiring::LoopOutcome{"completed", run.tracking.convergence_time, run.tracking.rms_last_second};
  return out;
}

TuneEvaluation judgeCandidate(const TuneProblem& p, CandidateRun run, std::optional<double> best_time,
                              double cut, bool (*stop_requested)()) {
  const auto judge_start = std::chrono::steady_clock::now();
  if (run.interrupted) throw TuneInterrupted();
  TuneEvaluation e = std::move(run.findings);
  const config::Scenario& s = run.scenario;
  // Wall time: the first part's (perhaps made on another thread, ahead) and this one's.
  const double first_part = e.load_time + e.run_time;
  const auto finish = [&] {
    e.value = tuneValue(e, s, p.torque_limit);
    e.wall_time = first_part + since(judge_start);
    return e;
  };
  const bool diverged = e.status == "diverged";
  if (!e.failed.empty() && !diverged) return finish();  // refused, eq. (12) with --require-condition
  // Judged up to the cut alone unless it converged before it: what is judged
  // is then the same however far the run went (its cut was this one or later).
  if (std::isfinite(cut) && !run.errors.empty() &&
      !(e.status == "completed" && e.convergence_time && *e.convergence_time < cut)) {
    const long long last = cutTick(cut, s.tickPeriod());
    if (diverged && static_cast<long long>(run.errors.size()) <= last) {
      e.feasible = false;
      return finish();  // diverged before the cut: as a run to its end says
    }
    const size_t k = std::min(static_cast<size_t>(last), run.errors.size() - 1);
    e.failed.clear();
    e.status = "cut";
    e.convergence_time.reset();
    e.judged_to = cut;
    e.final_error = run.errors[k];
    e.peak_torque = run.peaks[k];
    estimateFromEnvelope(e, run.errors, k, cut, s.tickPeriod(), s.metrics.tolerance);
    if (p.torque_limit > 0.0 && e.peak_torque > p.torque_limit * (1.0 + 1e-9)) {
      e.feasible = false;
      e.failed = "torque over the limit";
    }
    return finish();
  }
  if (diverged) {
    e.feasible = false;
    return finish();
  }
  if (!e.convergence_time || *e.convergence_time > s.metrics.convergence_deadline) {
    e.feasible = false;
    e.failed = "metric not met from the initial state";
    return finish();
  }
  if (p.torque_limit > 0.0 && e.peak_torque > p.torque_limit * (1.0 + 1e-9)) {
    e.feasible = false;
    e.failed = "torque over the limit";
    return finish();
  }
  // The costly check only for a candidate that would be the new best.
  if (best_time &&
      *e.convergence_time >= *best_time - std::max(kCheckedGain * *best_time, 2.0 * s.tickPeriod()))
    return finish();

  const auto check_start = std::chrono::steady_clock::now();
  const controller::SampledSimulation check = wiring::simulateSampledData(s, p.jobs, run.loop);
  e.check_time = since(check_start);
  if (stop_requested && stop_requested()) throw TuneInterrupted();
  e.sampled_verdict = check.verdict;
  e.sampled_why = check.why;
  for (const controller::SampledSimulation::Start& st : check.starts)
    e.start_times.push_back(st.sampled_time);
  const auto linearised_start = std::chrono::steady_clock::now();
  const controller::SampledDataCheck linearised = controller::checkSampledData(s);
  e.linearised_time = since(linearised_start);
  e.linearised_verdict = linearised.verdict;
  e.sufficient_rate = linearised.sufficient_rate;
  const bool starts_met = std::all_of(e.start_times.begin(), e.start_times.end(), [&](const auto& t) {
    return t && *t <= s.metrics.convergence_deadline;
  });
  if (!check.adequate() || !starts_met) {
    e.feasible = false;
    e.failed = !check.adequate() ? "sampled-data check " + check.verdict
                                 : "sampled-data check: a seeded start missed the metric";
    return finish();
  }
  e.feasible = true;
  return finish();
}

TuneEvaluation evaluateGains(const TuneProblem& p, const TuneGains& gains, std::optional<double> best_time,
                             bool (*stop_requested)()) {
  return judgeCandidate(p, runCandidate(p, gains, stop_requested), best_time,
                        std::numeric_limits<double>::infinity(), stop_requested);
}

controller::SampledDataCheck linearisedCheckOf(const TuneProblem& p, const TuneGains& gains) {
  std::vector<std::string> overrides = p.overrides;
  for (const std::string& o : gainOverrides(p.input, gains)) overrides.push_back(o);
  return controller::checkSampledData(config::loadScenario(p.scenario_path, overrides));
}

}  // namespace lagrange::tools
