// lagrange tune's pure parts: every registered controller's tunable gains
// (the controller seam, controller/registry.hpp), the search core
// (tools/tune/tune_search.hpp) and the objective's penalty bands
// (tools/tune/tune_evaluate.hpp).
#include "tools/tune/tune_search.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/controller_params.hpp"
#include "controller/registry.hpp"
#include "tools/tune/tune_evaluate.hpp"

namespace lagrange::tools {
namespace {

TEST(TunableGains, EveryRegisteredControllerDeclaresAtLeastOneWithAValidRange) {
  const std::vector<std::string> types = config::controllerTypes();
  // The seam's test-only controller is linked into this program too.
  ASSERT_NE(std::find(types.begin(), types.end(), "test_pd"), types.end());
  for (const std::string& type : types) {
    if (type == "external") continue;  // a program of the user's: no gains lagrange knows
    SCOPED_TRACE(type);
    const std::vector<controller::TunableGain>& gains = controller::tunableGains(type);
    ASSERT_FALSE(gains.empty());
    std::set<std::pair<std::string, bool>> names;  // a stage's kp is not stage 0's
    for (const controller::TunableGain& g : gains) {
      SCOPED_TRACE(g.name);
      EXPECT_TRUE(names.insert({g.name, g.per_stage}).second) << "declared twice";
      // Only the paper's chains have stages.
      if (g.per_stage) {
        EXPECT_TRUE(type == "cascaded" || type == "flexible" || type == "theorem1") << type;
      }
      EXPECT_GT(g.lower, 0.0);
      EXPECT_GT(g.upper, g.lower);
      EXPECT_GE(g.fallback, g.lower);
      EXPECT_LE(g.fallback, g.upper);
      // A kind of per-joint keys alone: a tunable gain is one of its keys.
      const config::ControllerRegistration* r = config::controllerRegistration(type);
      ASSERT_NE(r, nullptr);
      if (!r->section.read) {
        const bool declared = std::any_of(r->params.begin(), r->params.end(),
                                          [&](const config::ControllerParam& p) { return p.key == g.name; });
        EXPECT_TRUE(declared) << "not a key of controller." << type;
      }
    }
  }
  // The seam's controller declares the scalar case.
  const auto& test_pd = controller::tunableGains("test_pd");
  EXPECT_TRUE(std::any_of(test_pd.begin(), test_pd.end(), [](const auto& g) { return !g.per_joint; }));
}

controller::ControllerKind kindWithout(const std::string& type) {
  return {type,
          {{"kp", true, "stiffness"}},
          [](const config::Scenario&) -> std::unique_ptr<controller::Controller> { return nullptr; },
          {}};
}

TEST(TunableGains, RegistrationRefusesNoneOrABadRangeAndRegistersNothing) {
  EXPECT_THROW(controller::registerControllerKind(kindWithout("tune_test_none")), std::logic_error);
  EXPECT_THROW(controller::registerControllerKind(
                   controller::withTunable(kindWithout("tune_test_zero"), {{"kp", true, 0.0, 10.0, 1.0}})),
               std::logic_error);
  EXPECT_THROW(controller::registerControllerKind(controller::withTunable(kindWithout("tune_test_outside"),
                                                                          {{"kp", true, 1.0, 10.0, 20.0}})),
               std::logic_error);
  const std::vector<std::string> types = config::controllerTypes();
  for (const char* refused : {"tune_test_none", "tune_test_zero", "tune_test_outside"})
    EXPECT_EQ(std::find(types.begin(), types.end(), refused), types.end()) << refused;
}

// A bowl in log space with its bottom at `bottom`: what the search should find.
struct Bowl {
  std::vector<double> bottom;
  std::vector<std::vector<double>> calls = {};
  std::vector<SearchPhase> phases = {};
  double operator()(const std::vector<double>& x, SearchPhase phase) {
    calls.push_back(x);
    phases.push_back(phase);
    double f = 0.0;
    for (size_t i = 0; i < x.size(); ++i) f += std::pow(std::log(x[i] / bottom[i]), 2);
    return f;
  }
};

std::vector<SearchVariable> box(size_t n) {
  std::vector<SearchVariable> v;
  for (size_t i = 0; i < n; ++i) v.push_back({"g" + std::to_string(i), 0.01, 100.0, 1.0 + 0.5 * i});
  return v;
}

TEST(TuneSearch, StartsAtTheStartItselfThenFindsTheBottomWithinTheBudget) {
  Bowl bowl{{3.0, 0.2, 40.0}};
  SearchSettings s;
  s.seed = 7;
  s.max_evaluations = 300;
  const SearchOutcome out = search(box(3), s, [&](const auto& x, SearchPhase p) { return bowl(x, p); });
  ASSERT_FALSE(bowl.calls.empty());
  EXPECT_EQ(bowl.calls.front(), (std::vector<double>{1.0, 1.5, 2.0}));  // exactly, not exp(log(x))
  EXPECT_EQ(bowl.phases.front(), SearchPhase::kStart);
  EXPECT_LE(out.evaluations, 300);
  for (int budget : {37, 61, 95}) {  // never one over, whichever phase the budget ends in
    SearchSettings b = s;
    b.max_evaluations = budget;
    b.global_evaluations = 40;
    int calls = 0;
    Bowl eight{std::vector<double>(8, 2.0)};
    search(box(8), b, [&](const auto& x, SearchPhase p) {
      ++calls;
      return eight(x, p);
    });
    EXPECT_LE(calls, budget);
  }
  EXPECT_EQ(out.evaluations, static_cast<int>(bowl.calls.size()));
  EXPECT_TRUE(std::count(bowl.phases.begin(), bowl.phases.end(), SearchPhase::kLocal) > 0);
  for (const auto& x : bowl.calls)
    for (double v : x) {
      EXPECT_GE(v, 0.01 * (1 - 1e-12));
      EXPECT_LE(v, 100.0 * (1 + 1e-12));
    }
  ASSERT_EQ(out.best.size(), 3u);
  for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(std::log(out.best[i] / bowl.bottom[i]), 0.0, 0.05) << i;
}

TEST(TuneSearch, TheSameSeedGivesTheSamePointsAndALongerBudgetRepeatsAShorterOne) {
  SearchSettings s;
  s.seed = 3;
  s.max_evaluations = 40;
  s.global_evaluations = 25;
  Bowl a{{3.0, 0.2}}, b{{3.0, 0.2}}, longer{{3.0, 0.2}}, other{{3.0, 0.2}};
  search(box(2), s, [&](const auto& x, SearchPhase p) { return a(x, p); });
  search(box(2), s, [&](const auto& x, SearchPhase p) { return b(x, p); });
  EXPECT_EQ(a.calls, b.calls);
  SearchSettings more = s;
  more.max_evaluations = 80;
  search(box(2), more, [&](const auto& x, SearchPhase p) { return longer(x, p); });
  ASSERT_GE(longer.calls.size(), a.calls.size());
  EXPECT_TRUE(std::equal(a.calls.begin(), a.calls.end(), longer.calls.begin()));
  SearchSettings reseeded = s;
  reseeded.seed = 4;
  search(box(2), reseeded, [&](const auto& x, SearchPhase p) { return other(x, p); });
  EXPECT_NE(a.calls, other.calls);
}

TEST(TuneSearch, ManyGainsGetAShortGlobalPhaseAndLocalStepsOfAboutAFactorOfOnePointFive) {
  // 28 numbers (the Panda's): 60 global calls, not 290, then the local phase
  // from the best, whose first steps stay within a factor of e^0.4 (and
  // do not jump a quarter of the box, a factor of 10 in +-2 decades).
  const std::vector<SearchVariable> panda = box(28);
  Bowl bowl{std::vector<double>(28, 1.0)};
  SearchSettings s;
  s.max_evaluations = 100;
  search(panda, s, [&](const auto& x, SearchPhase p) { return bowl(x, p); });
  EXPECT_EQ(defaultGlobalEvaluations(28), kMostGlobal);
  EXPECT_EQ(defaultGlobalEvaluations(2), 30);
  // (CRS2's mutation step may evaluate two points before NLopt looks at its count.)
  const long global = std::count(bowl.phases.begin(), bowl.phases.end(), SearchPhase::kGlobal);
  EXPECT_GE(global, kMostGlobal);
  EXPECT_LE(global, kMostGlobal + 2);
  const auto first_local = std::find(bowl.phases.begin(), bowl.phases.end(), SearchPhase::kLocal);
  ASSERT_NE(first_local, bowl.phases.end());
  // The local phase's start is the best point so far; its next call one step from it.
  const size_t k = static_cast<size_t>(first_local - bowl.phases.begin());
  ASSERT_LT(k + 1, bowl.calls.size());
  for (size_t i = 0; i < 28; ++i)
    EXPECT_LE(std::abs(std::log(bowl.calls[k + 1][i] / bowl.calls[k][i])), kLocalStep + 1e-9) << i;
}

TEST(TuneSearch, ALookaheadChangesNoCallAndItsFirstPointIsTheNextCall) {
  // A bowl with a penalty step (as tune's bands): values the search sees far
  // apart, so that a guess could mislead it if the replay were wrong.
  const auto stepped = [](Bowl& b) {
    return [&b](const std::vector<double>& x, SearchPhase p) {
      const double f = b(x, p);
      return x[0] > 20.0 ? 3e6 + f : f;
    };
  };
  SearchSettings s;
  s.seed = 11;
  s.max_evaluations = 120;
  Bowl alone{{3.0, 0.2, 40.0}};
  const SearchOutcome one = search(box(3), s, stepped(alone));
  for (int lookahead : {2, 3, 5}) {
    SCOPED_TRACE(lookahead);
    SearchSettings ahead = s;
    ahead.lookahead = lookahead;
    Bowl with{{3.0, 0.2, 40.0}};
    std::vector<std::vector<std::vector<double>>> batches;
    const auto objective = stepped(with);
    const SearchOutcome two = search(
        box(3), ahead,
        [&](const std::vector<double>& x, SearchPhase p) {
          // Every call was handed over first, as the first point of the last batch.
          EXPECT_FALSE(batches.empty());
          if (!batches.empty()) {
            EXPECT_EQ(batches.back().front(), x);
          }
          return objective(x, p);
        },
        [&](const std::vector<std::vector<double>>& points) {
          EXPECT_LE(points.size(), static_cast<size_t>(lookahead));
          batches.push_back(points);
        });
    EXPECT_EQ(with.calls, alone.calls);
    EXPECT_EQ(with.phases, alone.phases);
    EXPECT_EQ(two.best, one.best);
    EXPECT_EQ(two.best_value, one.best_value);
    EXPECT_EQ(two.evaluations, one.evaluations);
    // The guesses that came true: CRS2's population (30 points here, drawn
    // before any value is looked at) is guessed whole, batch after batch.
    std::set<std::vector<double>> asked(with.calls.begin(), with.calls.end());
    size_t right = 0;
    for (const auto& batch : batches)
      right += static_cast<size_t>(
          std::count_if(batch.begin() + 1, batch.end(), [&](const auto& x) { return asked.count(x) > 0; }));
    EXPECT_GE(right, 25u);
  }
}

TEST(TuneSearch, AnObjectivesExceptionEndsTheSearchAsItIs) {
  struct Stop {};
  int calls = 0;
  SearchSettings s;
  s.max_evaluations = 100;
  EXPECT_THROW(search(box(2), s,
                      [&](const auto&, SearchPhase) -> double {
                        if (++calls == 5) throw Stop{};
                        return 1.0;
                      }),
               Stop);
  EXPECT_EQ(calls, 5);
}

TEST(TuneValue, PenaltyBandsOrderTheFailuresAboveEveryFeasibleTime) {
  config::Scenario s;
  s.metrics.tolerance = 1e-3;
  s.metrics.convergence_deadline = 5.0;
  TuneEvaluation ok;
  ok.convergence_time = 0.8;
  EXPECT_DOUBLE_EQ(tuneValue(ok, s, 100.0), 0.8);
  const auto failing = [&](const std::string& failed) {
    TuneEvaluation e;
    e.failed = failed;
    e.final_error = 0.5;
    e.peak_torque = 150.0;
    e.margin = -0.1;
    e.condition_lhs = 0.2;
    e.sampled_verdict = "slow";
    e.start_times = {0.9, std::nullopt, 1.0};
    return tuneValue(e, s, 100.0);
  };
  const std::vector<double> bands = {failing("sampled-data check slow"),
                                     failing("torque over the limit"),
                                     failing("metric not met from the initial state"),
                                     failing("diverged from the initial state"),
                                     failing("condition eq. (12) violated (--require-condition)"),
                                     failing("scenario refused: x")};
  EXPECT_GT(bands.front(), s.metrics.convergence_deadline);
  for (size_t i = 1; i < bands.size(); ++i) EXPECT_GT(bands[i], bands[i - 1]) << i;
  // Within a band, by how far it misses: more torque, a higher value.
  TuneEvaluation over;
  over.failed = "torque over the limit";
  over.peak_torque = 110.0;
  const double little = tuneValue(over, s, 100.0);
  over.peak_torque = 400.0;
  EXPECT_GT(tuneValue(over, s, 100.0), little);
  EXPECT_LT(tuneValue(over, s, 100.0), 2e6);
}

}  // namespace
}  // namespace lagrange::tools
