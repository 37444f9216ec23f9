#include "tools/tune/tune.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <set>

#include "tools/command_error.hpp"
#include "tools/tune/tune_ahead.hpp"
#include "tools/tune/tune_evaluate.hpp"
#include "tools/tune/tune_files.hpp"
#include "tools/tune/tune_search.hpp"
#include "util/error.hpp"
#include "util/jobs.hpp"

namespace lagrange::tools {

namespace fs = std::filesystem;

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }
bool stopRequested() { return g_stop != 0; }

// The confirm phase's most evaluations.
constexpr size_t kConfirmed = 3;

// The --minutes budget spent: the search ends as if its evaluations were.
struct BudgetSpent {};

std::string shortNumber(double v, const char* format = "%.4g") {
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

}  // namespace

int runTune(const TuneOptions& o) {
  const std::string who = "lagrange tune";
  TuneProblem p;
  nlohmann::ordered_json arguments;
  std::map<std::vector<double>, TuneEvaluation> cache,
      confirmed;  // read from tune.jsonl: the search's, confirm's
  try {
    if (o.out_dir.empty()) throw BadInput("expected --out DIR, the folder for tune.jsonl and tuned.yaml");
    if (!(o.span > 0.0))
      throw BadInput("--span " + shortNumber(o.span) + ": expected a positive number of decades");
    p = makeTuneProblem(o.scenario, o.overrides, o.span);
    p.require_condition = o.require_condition;
    if (o.require_condition && !p.kc)
      throw BadInput(
          "--require-condition: controller type '" + p.input.controller.type +
          "' has no eq. (12) to require; expected one of the paper's controllers (theorem1, cascaded, "
          "flexible), or no --require-condition");
    p.jobs = o.jobs;
    arguments = tuneArguments(p, o.seed, o.span, o.global);
    prepareTuneDir(o.out_dir, arguments);
    cache = readEvaluations(o.out_dir, SearchPhase::kStart);
    confirmed = readEvaluations(o.out_dir, SearchPhase::kConfirm);
  } catch (const std::exception& e) {
    return failWith(who, e);
  }
  g_stop = 0;
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);

  const int budget = o.evaluations > 0 ? o.evaluations
                     : o.minutes > 0.0 ? std::numeric_limits<int>::max()
                                       : kDefaultEvaluations;
  const auto started = std::chrono::steady_clock::now();
  const bool tty = isatty(STDERR_FILENO) != 0;
  std::vector<TuneEvaluation> seen;  // in the search's order
  std::optional<size_t> best;        // into seen: the fastest feasible
  int computed = 0, read = 0;
  std::map<std::vector<double>, TuneEvaluation> made;  // this run's, made or read: a repeated point's

  // The runs from the initial state, made ahead on -j threads (one per core by default).
  const int workers = util::jobsOrCores(o.jobs);
  CandidateRuns runs(p, workers, stopRequested);

  const SearchObjective objective = [&](const std::vector<double>& point, SearchPhase phase) {
    if (stopRequested()) throw TuneInterrupted();
    if (o.minutes > 0.0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() > 60.0 * o.minutes)
      throw BudgetSpent{};
    TuneEvaluation e;
    // A point the search repeats gets its first evaluation again (never a
    // second line); one tune.jsonl holds from a run before is read, not made.
    if (const auto m = made.find(point); m != made.end()) {
      e = m->second;
    } else if (const auto c = cache.find(point); c != cache.end()) {
      e = c->second;
      ++read;
      made.emplace(point, e);
    } else {
      const std::optional<double> best_time = best ? seen[*best].convergence_time : std::optional<double>();
      e = judgeCandidate(p, runs.take(point), best_time, stopRequested);
      ++computed;
      appendEvaluation(o.out_dir, evaluationJson(static_cast<int>(seen.size()), phase, e, p.torque_limit));
      made.emplace(point, e);
    }
    // Without saturation the limit is the input gains' own peak.
    if (phase == SearchPhase::kStart && !p.torque_from_saturation && std::isfinite(e.peak_torque) &&
        e.peak_torque > 0.0)
      p.torque_limit = e.peak_torque;
    seen.push_back(e);
    if (e.feasible == true && (!best || *e.convergence_time < *seen[*best].convergence_time))
      best = seen.size() - 1;
    if (!o.quiet && (tty || seen.size() % 10 == 0)) {
      std::cerr << (tty ? "\r\033[K" : "") << who << ": " << seen.size();
      if (budget != std::numeric_limits<int>::max()) std::cerr << "/" << budget;
      std::cerr << " evaluations (" << read << " read), best "
                << (best ? seconds(seen[*best].convergence_time) : std::string("none yet")) << " (input "
                << seconds(seen.front().convergence_time) << ")" << (tty ? "" : "\n") << std::flush;
    }
    return e.value;
  };

  // The points the search asks next: those not already made or read, run ahead.
  const SearchLookahead lookahead = [&](const std::vector<std::vector<double>>& points) {
    std::vector<std::vector<double>> to_run;
    for (const std::vector<double>& point : points)
      if (made.count(point) == 0 && cache.count(point) == 0) to_run.push_back(point);
    runs.ahead(to_run);
  };

  SearchSettings settings;
  settings.seed = o.seed;
  settings.max_evaluations = budget;
  settings.global_evaluations = o.global;
  settings.lookahead = workers;
  bool interrupted = false;
  try {
    search(p.variables, settings, objective, lookahead);
  } catch (const BudgetSpent&) {
  } catch (const TuneInterrupted&) {
    interrupted = true;
  } catch (const std::exception& e) {
    if (tty && !o.quiet) std::cerr << "\n";
    return failWith(who, e);
  }
  runs.finish();  // no guess of the search's runs beside the confirm phase's checks
  // The confirm phase: the fastest runs the search left unchecked (they
  // did not beat the best by kCheckedGain), checked now, fastest first,
  // until one passes or kConfirmed were tried.
  const size_t searched = seen.size();
  if (!interrupted && best) {
    std::vector<size_t> unchecked;
    std::set<std::vector<double>> queued;
    for (size_t i = 0; i < seen.size(); ++i)
      if (!seen[i].feasible && seen[i].convergence_time &&
          *seen[i].convergence_time < *seen[*best].convergence_time &&
          queued.insert(flattened(seen[i].gains)).second)
        unchecked.push_back(i);
    std::stable_sort(unchecked.begin(), unchecked.end(), [&](size_t a, size_t b) {
      return *seen[a].convergence_time < *seen[b].convergence_time;
    });
    if (unchecked.size() > kConfirmed) unchecked.resize(kConfirmed);
    try {
      for (const size_t i : unchecked) {
        if (stopRequested()) throw TuneInterrupted();
        const std::vector<double> point = flattened(seen[i].gains);
        TuneEvaluation e;
        if (const auto c = confirmed.find(point); c != confirmed.end()) {
          e = c->second;
          ++read;
        } else {
          e = evaluateGains(p, seen[i].gains, std::nullopt, stopRequested);
          ++computed;
          appendEvaluation(o.out_dir, evaluationJson(static_cast<int>(seen.size()), SearchPhase::kConfirm, e,
                                                     p.torque_limit));
        }
        seen.push_back(e);
        if (e.feasible == true) {
          best = seen.size() - 1;
          break;
        }
      }
    } catch (const TuneInterrupted&) {
      interrupted = true;
    } catch (const std::exception& e) {
      return failWith(who, e);
    }
  }
  if (tty && !o.quiet && !seen.empty()) std::cerr << "\n";

  nlohmann::ordered_json result;
  result["evaluations"] = searched;
  result["confirmed"] = seen.size() - searched;
  result["computed"] = computed;
  result["read"] = read;
  result["interrupted"] = interrupted;
  result["runs"] = {{"made", runs.made()}, {"ahead", runs.madeAhead()}, {"used", runs.used()}};
  result["input"] = seen.empty() ? nlohmann::json() : nlohmann::json(side(seen.front()));
  result["best"] = best ? nlohmann::json(side(seen[*best])) : nlohmann::json();
  try {
    writeTuneJson(o.out_dir, arguments, result);
    const std::string not_drawn = drawFront(o.out_dir, readEvaluationLines(o.out_dir));
    if (!not_drawn.empty() && !o.quiet) std::cerr << who << ": " << not_drawn << "\n";
    if (interrupted) {
      std::cerr << who << ": interrupted after " << seen.size() << " evaluations; run the same command again "
                << "to resume (" << o.out_dir << "/tune.jsonl keeps them)\n";
      return kExitInterrupted;
    }
    if (!best) {
      std::cerr << who << ": no gains passed every check in " << seen.size() << " evaluations; what binds:\n";
      for (const std::string& line : whatBinds(p, seen)) std::cerr << "  - " << line << "\n";
      return kExitFailed;
    }
    writeTunedYaml(o.out_dir, p, seen[*best].gains);
  } catch (const std::exception& e) {
    return failWith(who, e);
  }
  if (!o.quiet) {
    std::cout << who << ": " << o.scenario << " (" << p.input.controller.type << ", " << p.variables.size()
              << " gains searched), " << seen.size() << " evaluations: " << computed << " computed, " << read
              << " read from " << o.out_dir << "/tune.jsonl\n";
    printSummary(seen.front(), seen[*best], p);
    if (*best == 0) std::cout << "  no candidate beat the input's gains: tuned.yaml holds them\n";
    std::cout << "wrote " << o.out_dir << "/tuned.yaml (lagrange run / check-gains it as it is), tune.jsonl, "
              << "tune.json, front.png\n";
  }
  return kExitOk;
}

}  // namespace lagrange::tools
