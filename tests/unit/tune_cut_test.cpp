// lagrange tune's cut (tools/tune/tune_evaluate.hpp, docs/tuning.md "The
// objective"): in the local phase a candidate's run is stopped once it can no
// longer beat the best, and judged on what it did up to the cut. Runs made
// ahead on other threads stop at an older, later cut, so what is judged must
// not depend on where the run itself stopped -- else one seed would not give
// one tune.jsonl whatever -j. In process, on the 2-joint arm's short runs.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "support/temp_dir.hpp"
#include "tools/tune/tune_evaluate.hpp"
#include "tools/tune/tune_files.hpp"
#include "util/error.hpp"

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
