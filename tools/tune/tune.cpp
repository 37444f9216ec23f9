#include "tools/tune/tune.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
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
#include "tools/tune/tune_report.hpp"
#include "tools/tune/tune_search.hpp"
#include "tools/tune/tune_slurm.hpp"
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

}  // namespace

TuneProblem checkedTuneProblem(const TuneOptions& o) {
  if (o.out_dir.empty()) throw BadInput("expected --out DIR, the folder for tune.jsonl and tuned.yaml");
  if (!(o.span > 0.0))
    throw BadInput("--span " + shortNumber(o.span) + ": expected a positive number of decades");
  TuneProblem p = makeTuneProblem(o.scenario, o.overrides, o.span);
  p.require_condition = o.require_condition;
  if (o.full_runs) p.cut_factor = 0.0;
  if (o.require_condition && !p.kc)
    throw BadInput(
        "--require-condition: controller type '" + p.input.controller.type +
        "' has no eq. (12) to require; expected one of the paper's controllers (theorem1, cascaded, "
        "flexible), or no --require-condition");
  p.jobs = o.jobs;
  return p;
}

int runTune(const TuneOptions& o) {
  if (o.slurm) return runTuneSlurm(o);
  const std::string who = "lagrange tune";
  const wiring::SlurmOptions& s = o.slurm_options;
  const char* slurm_only = o.starts != 0            ? "--starts"
                           : s.no_wait              ? "--no-wait"
                           : !s.partition.empty()   ? "--partition"
                           : !s.time_limit.empty()  ? "--time"
                           : !s.account.empty()     ? "--account"
                           : !s.sbatch_args.empty() ? "--sbatch-arg"
                                                    : nullptr;
  if (slurm_only)
    return failWith(who, BadInput(std::string(slurm_only) +
                                  " is an option of a tune on Slurm; expected --slurm "
                                  "with it, or no " +
                                  slurm_only));
  TuneProblem p;
  nlohmann::ordered_json arguments;
  std::map<std::vector<double>, TuneEvaluation> cache,
      confirmed;  // read from tune.jsonl: the search's, confirm's
  try {
    p = checkedTuneProblem(o);
    if (fs::exists(fs::symlink_status(fs::path(o.out_dir) / "starts.json")))
      throw BadInput(o.out_dir +
                     " holds a tune on Slurm (starts.json); expected --slurm to resume it, lagrange tune "
                     "collect " +
                     o.out_dir + ", or another --out");
    arguments = tuneArguments(p, o.seed, o.span, o.global);
    prepareTuneDir(o.out_dir, arguments);
    // The arguments before the first evaluation, the result null until the
    // end: a tune killed (SIGKILL, a Slurm time limit) is resumed from them.
    writeTuneJson(o.out_dir, arguments, nullptr);
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

  // The runs from the initial state, made ahead on -j threads (one per core
  // by default), each stopped at the cut of the best known when it gets there.
  const int workers = util::jobsOrCores(o.jobs);
  std::atomic<double> cut_time{std::numeric_limits<double>::infinity()};
  CandidateRuns runs(p, workers, stopRequested, &cut_time);

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
      // The local phase's runs are cut (the global phase's judged to their
      // end: its values choose where the descent starts). The cut only
      // comes earlier along the sequence: a run made ahead at an older,
      // later cut is judged the same (runCandidate).
      const double cut =
          phase == SearchPhase::kLocal ? cutTime(p, best_time) : std::numeric_limits<double>::infinity();
      cut_time.store(cut);
      e = judgeCandidate(p, runs.take(point), best_time, cut, stopRequested);
      ++computed;
      appendEvaluation(o.out_dir, evaluationJson(static_cast<int>(seen.size()), phase, e, p.torque_limit));
      made.emplace(point, e);
    }
    // Without saturation the limit is the input gains' own peak.
    if (phase == SearchPhase::kStart && !p.torque_from_saturation && std::isfinite(e.peak_torque) &&
        e.peak_torque > 0.0)
      p.torque_limit = e.peak_torque;
    seen.push_back(e);
    if (e.feasible == true && (!best || *e.convergence_time < *seen[*best].convergence_time)) {
      best = seen.size() - 1;
      if (phase == SearchPhase::kLocal) cut_time.store(cutTime(p, e.convergence_time));
    }
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
  result["budget"] = tuneBudget(o.evaluations, o.minutes);
  result["runs"] = {
      {"made", runs.made()}, {"ahead", runs.madeAhead()}, {"used", runs.used()}, {"cut", runs.cut()}};
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
