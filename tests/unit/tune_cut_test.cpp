// lagrange tune's cut (tools/tune/tune_evaluate.hpp, docs/tuning.md "The
// objective"): in the local phase a candidate's run is stopped once it can no
// longer beat the best, and judged on what it did up to the cut. Runs made
// ahead on other threads stop at an older, later cut, so what is judged must
// not depend on where the run itself stopped -- else one seed would not give
// one tune.jsonl whatever -j. In process, on the 2-joint arm's short runs.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include "controller/paper_section.hpp"
#include "support/temp_dir.hpp"
#include "tools/tune/tune_evaluate.hpp"
#include "tools/tune/tune_files.hpp"
#include "util/error.hpp"
#include "wiring/sampled_simulation.hpp"

namespace lagrange::tools {
namespace {

const std::string kScenario = std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml";
constexpr double kNoCut = std::numeric_limits<double>::infinity();

TuneProblem shortProblem() {
  return makeTuneProblem(kScenario,
                         {"duration=2", "plant.physics_step=1e-4", "metrics.convergence_deadline=1.5"}, 2.0);
}

// What tune.jsonl keeps of an evaluation, its wall times aside.
nlohmann::ordered_json judged(const TuneEvaluation& e, double limit) {
  nlohmann::ordered_json j = evaluationJson(0, SearchPhase::kLocal, e, limit);
  j.erase("wall_time");
  j.erase("times");
  return j;
}

TEST(TuneCut, ACandidateIsJudgedTheSameWhereverItsRunStopped) {
  TuneProblem p = shortProblem();
  const TuneEvaluation input =
      judgeCandidate(p, runCandidate(p, p.input_gains, nullptr), std::nullopt, kNoCut, nullptr);
  ASSERT_TRUE(input.convergence_time);
  const double best = *input.convergence_time;
  p.torque_limit = input.peak_torque;  // as tune sets it without saturation
  const double cut = cutTime(p, best);
  EXPECT_DOUBLE_EQ(cut, best);  // cut_factor 1, the best before the deadline
  EXPECT_EQ(cutTime(p, std::nullopt), kNoCut);

  // A slower candidate: the input's stiffness halved.
  TuneGains slower = p.input_gains;
  for (auto& [name, values] : slower)
    if (name == "kp")
      for (double& v : values) v *= 0.5;
  std::atomic<double> at_cut{cut}, later{1.4 * cut};
  const CandidateRun whole = runCandidate(p, slower, nullptr);
  const CandidateRun stopped = runCandidate(p, slower, nullptr, &at_cut);
  const CandidateRun stopped_later = runCandidate(p, slower, nullptr, &later);
  ASSERT_TRUE(whole.findings.convergence_time);
  ASSERT_GT(*whole.findings.convergence_time, 1.4 * cut);  // so both cut runs were stopped
  EXPECT_EQ(whole.findings.status, "completed");
  EXPECT_EQ(stopped.findings.status, "cut");
  EXPECT_EQ(stopped_later.findings.status, "cut");
  // Stopped where the rule says: the tick whose next sample reaches the cut
  // (its error above the tolerance there), each later one recorded up to the deadline.
  EXPECT_EQ(stopped.errors.size(), static_cast<size_t>(cutTick(cut, p.input.tickPeriod())) + 1);
  EXPECT_LT(stopped.errors.size(), stopped_later.errors.size());
  EXPECT_LT(stopped_later.errors.size(), whole.errors.size());

  const TuneEvaluation a = judgeCandidate(p, whole, best, cut, nullptr);
  const TuneEvaluation b = judgeCandidate(p, stopped, best, cut, nullptr);
  const TuneEvaluation c = judgeCandidate(p, stopped_later, best, cut, nullptr);
  EXPECT_EQ(judged(a, p.torque_limit), judged(b, p.torque_limit));
  EXPECT_EQ(judged(a, p.torque_limit), judged(c, p.torque_limit));
  EXPECT_EQ(a.status, "cut");
  ASSERT_TRUE(a.judged_to);
  EXPECT_EQ(*a.judged_to, cut);
  EXPECT_FALSE(a.convergence_time);
  EXPECT_FALSE(a.feasible);
  // Worse than the best, and by its estimate: later than the cut, earlier
  // than where it really converged? Not promised -- only that it ranks after
  // every time known.
  EXPECT_GT(a.value, best);
  EXPECT_LT(a.value, 1e5);  // below every penalty band

  // Judged to its end, the same run keeps its real convergence time.
  const TuneEvaluation uncut = judgeCandidate(p, whole, best, kNoCut, nullptr);
  EXPECT_EQ(uncut.convergence_time, whole.findings.convergence_time);
  EXPECT_FALSE(uncut.judged_to);
}

TEST(TuneCut, ACandidateThatBeatsTheBestIsNeverCut) {
  TuneProblem p = shortProblem();
  // A best 40 % slower than the input's own time: the input's gains beat it.
  const CandidateRun first = runCandidate(p, p.input_gains, nullptr);
  ASSERT_TRUE(first.findings.convergence_time);
  const double best = 1.4 * *first.findings.convergence_time;
  std::atomic<double> at_cut{cutTime(p, best)};
  const CandidateRun run = runCandidate(p, p.input_gains, nullptr, &at_cut);
  EXPECT_EQ(run.findings.status, "completed");
  const TuneEvaluation e = judgeCandidate(p, run, best, cutTime(p, best), nullptr);
  EXPECT_FALSE(e.judged_to);
  EXPECT_EQ(e.convergence_time, first.findings.convergence_time);
  EXPECT_EQ(e.feasible, true);  // checked (it beat the best), and the shipped gains pass
}

// A run as runCandidate leaves it, by hand: `ticks` samples of ||q~|| =
// error(k), the torque's peak 10 N m, its status and convergence time.
CandidateRun handMadeRun(const TuneProblem& p, size_t ticks, const std::function<double(size_t)>& error,
                         const std::string& status, std::optional<double> convergence_time = std::nullopt) {
  CandidateRun run;
  run.scenario = p.input;
  run.findings.gains = p.input_gains;
  run.findings.status = status;
  run.findings.convergence_time = convergence_time;
  run.findings.peak_torque = 10.0;
  run.findings.final_error = error(ticks - 1);
  if (status == "diverged") run.findings.failed = "diverged from the initial state: by hand";
  for (size_t k = 0; k < ticks; ++k) {
    run.errors.push_back(error(k));
    run.peaks.push_back(10.0);
  }
  return run;
}

TEST(TuneCut, ADivergenceCountsOnlyBeforeTheCutTickAndALateConvergenceIsCut) {
  TuneProblem p = shortProblem();
  p.torque_limit = 100.0;
  const double period = p.input.tickPeriod(), best = 0.9, cut = cutTime(p, best);
  const size_t last = static_cast<size_t>(cutTick(cut, period));
  const auto decaying = [&](size_t k) { return 0.5 * std::exp(-2.0 * static_cast<double>(k) * period); };
  // Diverged with its last sample before the cut tick: as a run to its end says.
  const TuneEvaluation early =
      judgeCandidate(p, handMadeRun(p, last, decaying, "diverged"), best, cut, nullptr);
  EXPECT_EQ(early.status, "diverged");
  EXPECT_EQ(early.feasible, false);
  EXPECT_GE(early.value, 3e6);
  // Diverged at the cut tick or after: a run stopped at the cut would not have seen it.
  for (const size_t ticks : {last + 1, last + 200}) {
    const TuneEvaluation late =
        judgeCandidate(p, handMadeRun(p, ticks, decaying, "diverged"), best, cut, nullptr);
    EXPECT_EQ(late.status, "cut") << ticks;
    EXPECT_TRUE(late.failed.empty()) << ticks;
    EXPECT_DOUBLE_EQ(late.final_error, decaying(last)) << ticks;
    ASSERT_TRUE(late.estimated_time) << ticks;
    EXPECT_GT(late.value, cut) << ticks;
  }
  // Completed, converging at the cut or later: judged as a cut run; before it: its time.
  const TuneEvaluation at_cut =
      judgeCandidate(p, handMadeRun(p, 1501, decaying, "completed", cut), best, cut, nullptr);
  EXPECT_EQ(at_cut.status, "cut");
  EXPECT_FALSE(at_cut.convergence_time);
  const TuneEvaluation before =
      judgeCandidate(p, handMadeRun(p, 1501, decaying, "completed", 0.95 * cut), best, cut, nullptr);
  EXPECT_EQ(before.status, "completed");
  EXPECT_EQ(before.convergence_time, 0.95 * cut);
  EXPECT_FALSE(before.judged_to);
}

TEST(TuneCut, AnEstimateIsAboveTheCutAndTheTorqueBeforeItCounts) {
  TuneProblem p = shortProblem();
  p.torque_limit = 100.0;
  const double period = p.input.tickPeriod(), best = 0.9, cut = cutTime(p, best);
  const double tolerance = p.input.metrics.tolerance;
  // Below the tolerance over the last quarter (above it only after the cut):
  // the estimate stays above the best's time, never a tie with it.
  const auto dips = [&](size_t k) {
    return static_cast<double>(k) * period < 0.7 * cut ? 0.1 : 0.5 * tolerance;
  };
  const TuneEvaluation dipped =
      judgeCandidate(p, handMadeRun(p, 1501, dips, "completed"), best, cut, nullptr);
  ASSERT_TRUE(dipped.estimated_time);
  EXPECT_GT(*dipped.estimated_time, cut);
  EXPECT_GT(dipped.value, best);
  // Not decaying: after every estimate, below every band.
  const TuneEvaluation flat = judgeCandidate(p,
                                             handMadeRun(
                                                 p, 1501, [](size_t) { return 0.1; }, "completed"),
                                             best, cut, nullptr);
  EXPECT_FALSE(flat.estimated_time);
  EXPECT_GT(flat.value, cut + 1e4);
  EXPECT_LT(flat.value, 1e5);
  // Over the torque limit before the cut: the torque band.
  CandidateRun strong = handMadeRun(
      p, 1501, [](size_t) { return 0.1; }, "completed");
  strong.peaks.assign(strong.peaks.size(), 150.0);
  const TuneEvaluation over = judgeCandidate(p, strong, best, cut, nullptr);
  EXPECT_EQ(over.failed, "torque over the limit");
  EXPECT_GE(over.value, 1e6);
  EXPECT_LT(over.value, 2e6);
}

// A candidate's own run, made to its end, is the sampled-data check's loop
// from the initial state bit for bit: the check takes it instead of
// simulating it again, and says the same, number for number.
TEST(TuneCheck, ACandidatesRunStandsForTheChecksLoopFromTheInitialState) {
  const TuneProblem p = shortProblem();
  const CandidateRun run = runCandidate(p, p.input_gains, nullptr);
  ASSERT_TRUE(run.loop);
  EXPECT_EQ(run.loop->status, "completed");
  const controller::SampledSimulation again = wiring::simulateSampledData(run.scenario, 1);
  const controller::SampledSimulation reused = wiring::simulateSampledData(run.scenario, 1, run.loop);
  EXPECT_EQ(reused.verdict, again.verdict);
  EXPECT_EQ(reused.why, again.why);
  EXPECT_EQ(reused.fine_rate, again.fine_rate);
  ASSERT_EQ(reused.starts.size(), again.starts.size());
  for (size_t i = 0; i < again.starts.size(); ++i) {
    EXPECT_EQ(reused.starts[i].sampled_time, again.starts[i].sampled_time) << i;
    EXPECT_EQ(reused.starts[i].sampled_error, again.starts[i].sampled_error) << i;
    EXPECT_EQ(reused.starts[i].fine_time, again.starts[i].fine_time) << i;
    EXPECT_EQ(reused.starts[i].verdict, again.starts[i].verdict) << i;
  }
  // It is what the check reads (a run said to have converged later shows there) ...
  wiring::LoopOutcome later = *run.loop;
  later.time = *later.time + 0.25;
  EXPECT_EQ(wiring::simulateSampledData(run.scenario, 1, later).starts.front().sampled_time, later.time);
  // ... but not for a realtime scenario, whose sampled loop has a period of delay.
  config::Scenario realtime = run.scenario;
  realtime.mode = config::Mode::kRealtime;
  EXPECT_NE(wiring::simulateSampledData(realtime, 1, later).starts.front().sampled_time, later.time);
  // A cut run did not go to its end: nothing to reuse.
  std::atomic<double> early{0.1};
  EXPECT_FALSE(runCandidate(p, p.input_gains, nullptr, &early).loop);
}

// A chain's later stages are searched too: each stage's kp, kd, a, b per
// joint, named stages[i].KEY. They reach the scenario as controller.stages
// whole (a list is replaced whole), each stage's other keys kept, and
// tuned.yaml writes them so.
class TuneStages : public testing::TempDirTest {};

TEST_F(TuneStages, AChainsStagesAreSearchedAndWrittenWithTheirOtherKeys) {
  const std::string flexible = std::string(LAGRANGE_SOURCE_DIR) + "/configs/double_pendulum_flexible.yaml";
  const TuneProblem p = makeTuneProblem(flexible, {"duration=1"}, 2.0);
  std::vector<std::string> labels;
  for (const SearchVariable& v : p.variables) labels.push_back(v.label);
  ASSERT_EQ(labels.size(),
            24u);  // stage 0 and the two stages of xi_1 = K q2, xi_2 = K q2': 3 x 4 gains x 2 joints
  EXPECT_EQ(labels[8], "stages[0].kp[0]");
  EXPECT_EQ(labels[23], "stages[1].b[1]");

  // The input's gains put back give the input scenario, key for key.
  std::vector<std::string> overrides = {"duration=1"};
  for (const std::string& o : gainOverrides(p.input, p.input_gains)) overrides.push_back(o);
  EXPECT_EQ(config::toYaml(config::loadScenario(flexible, overrides)), config::toYaml(p.input));

  // Another stage gain: it alone changes, the stages' bumpless starts stay.
  TuneGains gains = p.input_gains;
  for (auto& [name, values] : gains)
    if (name == "stages[1].kp") values = {123.5, 77.25};
  overrides = {"duration=1"};
  for (const std::string& o : gainOverrides(p.input, gains)) overrides.push_back(o);
  const config::Scenario tuned = config::loadScenario(flexible, overrides);
  const controller::PaperSettings was = controller::paperSettings(p.input),
                                  is = controller::paperSettings(tuned);
  ASSERT_EQ(is.stages.size(), 2u);
  EXPECT_EQ(is.stages[1].kp, (Eigen::Vector2d() << 123.5, 77.25).finished());
  EXPECT_EQ(is.stages[0].kp, was.stages[0].kp);
  EXPECT_EQ(is.stages[1].a, was.stages[1].a);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(was.stage_starts[i].bumpless) << i;
    EXPECT_TRUE(is.stage_starts[i].bumpless) << i;
  }
  // tuned.yaml, run as it is, has that controller (its other sections the
  // input's, the URDF's path anchored to the input's folder).
  writeTunedYaml(dir_, p, gains);
  const auto controllerOf = [](const config::Scenario& s) {
    return YAML::Dump(YAML::Load(config::toYaml(s))["controller"]);
  };
  EXPECT_EQ(controllerOf(config::loadScenario(dir_ + "/tuned.yaml", {"duration=1"})), controllerOf(tuned));

  // A rigid arm has no stages: stage 0's four gains per joint alone.
  EXPECT_EQ(shortProblem().variables.size(), 8u);
}

class TuneCutFolder : public testing::TempDirTest {};

TEST_F(TuneCutFolder, ATuneOfTheObjectiveBeforeTheCutIsNotResumed) {
  const TuneProblem p = shortProblem();
  nlohmann::ordered_json before = tuneArguments(p, 1, 2.0, 0);
  before.erase("cut");
  writeTuneJson(dir_, before, nullptr);
  std::ofstream(std::filesystem::path(dir_) / "tune.jsonl") << "{}\n";
  try {
    prepareTuneDir(dir_, tuneArguments(p, 1, 2.0, 0));
    FAIL() << "resumed";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("older lagrange"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("another --out, or --full-runs"), std::string::npos) << e.what();
  }
  // With --full-runs (no cut: that tune's objective), it is resumed.
  TuneProblem full = p;
  full.cut_factor = 0.0;
  EXPECT_TRUE(tuneArguments(full, 1, 2.0, 0).at("cut").is_null());
  EXPECT_NO_THROW(prepareTuneDir(dir_, tuneArguments(full, 1, 2.0, 0)));
  // The same arguments, with the cut: resumed.
  writeTuneJson(dir_, tuneArguments(p, 1, 2.0, 0), nullptr);
  EXPECT_NO_THROW(prepareTuneDir(dir_, tuneArguments(p, 1, 2.0, 0)));
}

}  // namespace
}  // namespace lagrange::tools
