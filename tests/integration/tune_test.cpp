// `lagrange tune` end to end on the 2-joint arm with a budget of seconds
// (docs/tuning.md): a tuned scenario that runs and passes check-gains, a
// resume that reads instead of recomputing, the refusal when the rate cannot
// be met, and one seed's determinism. The runs are in process: no LCM.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/launch.hpp"
#include "support/temp_dir.hpp"
#include "support/tune_files.hpp"

namespace lagrange::testing {
namespace {

const std::string kScenario = std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml";
// Short runs: 2 s at a coarser physics step, the metric by 1.5 s (the
// shipped gains converge at about 0.9 s).
const std::string kShort =
    "--set duration=2 --set plant.physics_step=1e-4 --set metrics.convergence_deadline=1.5 ";

RunResult tune(const std::string& out, const std::string& extra, int jobs = 2) {
  return lagrange("tune " + quote(kScenario) + " --out " + quote(out) + " " + kShort + "-j " +
                  std::to_string(jobs) + " " + extra);
}

class Tune : public TempDirTest {};

TEST_F(Tune, TheTunedScenarioRunsAsItIsAndCheckGainsPassesIt) {
  const std::string out = dir_ + "/tuned";
  const RunResult r = tune(out, "--evaluations 12 --global 6");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("convergence time"), std::string::npos) << r.output;
  const nlohmann::json best = tuneResult(out).at("best");
  EXPECT_EQ(best.at("feasible"), true);
  EXPECT_EQ(best.at("sampled_verdict"), "adequate");
  // No slower than the input's gains, which are where the search starts.
  EXPECT_LE(best.at("convergence_time").get<double>(),
            tuneResult(out).at("input").at("convergence_time").get<double>());
  EXPECT_TRUE(std::filesystem::exists(out + "/front.png"));
  // The best is the fastest that passed every check; a faster run the
  // search left unchecked was confirmed (and failed), unless the confirm
  // phase's three were spent.
  const std::vector<nlohmann::json> all = tuneLines(out);
  std::vector<nlohmann::json> confirmed;
  for (const nlohmann::json& l : all)
    if (l.at("phase") == "confirm") confirmed.push_back(l.at("gains"));
  EXPECT_LE(confirmed.size(), 3u);
  const double best_time = best.at("convergence_time").get<double>();
  for (const nlohmann::json& l : all) {
    if (l.at("feasible") == true) {
      EXPECT_GE(l.at("convergence_time").get<double>(), best_time);
    }
    if (l.at("feasible").is_null() && l.at("convergence_time").is_number() &&
        l.at("convergence_time").get<double>() < best_time && confirmed.size() < 3) {
      EXPECT_NE(std::find(confirmed.begin(), confirmed.end(), l.at("gains")), confirmed.end()) << l;
    }
  }

  const RunResult run =
      lagrange("run " + quote(out + "/tuned.yaml") + " --mode inproc -q --out " + quote(dir_ + "/run"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir_ + "/run/summary.json"));
  EXPECT_DOUBLE_EQ(summary.at("tracking").at("convergence_time").get<double>(),
                   best.at("convergence_time").get<double>());
  const RunResult check = lagrange("check-gains " + quote(out + "/tuned.yaml"));
  EXPECT_EQ(check.exit_code, 0) << check.output;
  for (const char* word : {"UNSTABLE", "INADEQUATE", "DIVERGES"})
    EXPECT_EQ(check.output.find(word), std::string::npos) << word << "\n" << check.output;
}

TEST_F(Tune, ARerunWithALargerBudgetReadsTheEvaluationsMadeAndComputesOnlyTheRest) {
  const std::string out = dir_ + "/resumed";
  ASSERT_EQ(tune(out, "--evaluations 10 --global 30").exit_code, 0);
  const std::vector<nlohmann::json> first = tuneLines(out);
  ASSERT_FALSE(first.empty());
  const RunResult again = tune(out, "--evaluations 20 --global 30");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  const nlohmann::json r = tuneResult(out);
  EXPECT_EQ(r.at("evaluations"), 20);
  // Every line of the first run's search read, none recomputed (its confirm
  // lines are read only where the longer search confirms the same gains).
  const size_t searched = static_cast<size_t>(std::count_if(
      first.begin(), first.end(), [](const nlohmann::json& l) { return l.at("phase") != "confirm"; }));
  EXPECT_GE(r.at("read").get<size_t>(), searched);
  EXPECT_LE(r.at("read").get<size_t>(), first.size());
  const std::vector<nlohmann::json> after = tuneLines(out);
  EXPECT_EQ(after.size(), first.size() + r.at("computed").get<size_t>());
  for (size_t i = 0; i < first.size(); ++i) EXPECT_EQ(after[i], first[i]) << i;
  // Other arguments in the same folder: refused, naming the one that differs.
  const RunResult other = tune(out, "--evaluations 20 --global 30 --seed 9");
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("seed"), std::string::npos) << other.output;
}

// Ctrl-C while the runs are made ahead on two threads: exit 130 at once, the
// evaluations made kept, and a resume gives what an uninterrupted tune gives.
TEST_F(Tune, AnInterruptWhileRunsAreMadeAheadKeepsWhatWasMadeAndResumesToTheSameEvaluations) {
  const std::string out = dir_ + "/interrupted", whole = dir_ + "/whole";
  const RunResult stopped =
      shell("timeout --preserve-status -s INT 5 " + kBin + "/lagrange tune " + quote(kScenario) + " --out " +
            quote(out) + " " + kShort + "-j 2 --evaluations 2000 --global 20 -q");
  ASSERT_EQ(stopped.exit_code, 130) << stopped.output;  // the interrupt came, and was said
  EXPECT_NE(stopped.output.find("interrupted after"), std::string::npos) << stopped.output;
  EXPECT_TRUE(tuneResult(out).at("interrupted").get<bool>());
  const std::vector<nlohmann::json> kept = tuneLines(out);  // every line whole (tuneLines() parses each)
  ASSERT_GT(kept.size(), 3u);
  ASSERT_LT(kept.size(), 1000u) << "not interrupted midway";
  const int budget = static_cast<int>(kept.size()) + 5;
  const std::string more = "--evaluations " + std::to_string(budget) + " --global 20";
  const RunResult resumed = tune(out, more, 2);
  ASSERT_LE(resumed.exit_code, 1) << resumed.output;
  ASSERT_LE(tune(whole, more, 1).exit_code, 1);
  EXPECT_GE(tuneResult(out).at("read").get<size_t>(), kept.size());
  const std::vector<nlohmann::json> a = tuneLines(out), b = tuneLines(whole);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].at("gains"), b[i].at("gains")) << i;
    EXPECT_EQ(a[i].at("value"), b[i].at("value")) << i;
  }
}

TEST_F(Tune, ARateNoGainsCanMeetIsRefusedNamingTheRate) {
  const RunResult r = tune(dir_ + "/slow", "--set plant.publish_rate=20 --evaluations 8 --global 6");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("no gains passed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("20 Hz"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("would suffice"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/slow/tuned.yaml"));
}

// One seed, the same evaluations, whether the candidates' runs are made one
// at a time (-j 1) or ahead of the search on two threads (-j 2).
TEST_F(Tune, OneSeedGivesTheSameEvaluationsWhateverTheJobs) {
  // 20 evaluations: the local phase's runs are cut at the best time, those
  // made ahead at an older, later one (tools/tune/tune_evaluate.hpp).
  ASSERT_EQ(tune(dir_ + "/a", "--evaluations 20 --global 8 --seed 5", 1).exit_code, 0);
  ASSERT_EQ(tune(dir_ + "/b", "--evaluations 20 --global 8 --seed 5", 2).exit_code, 0);
  const std::vector<nlohmann::json> a = tuneLines(dir_ + "/a"), b = tuneLines(dir_ + "/b");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 3u);
  long cut = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    nlohmann::json line_a = a[i], line_b = b[i];
    for (nlohmann::json* line : {&line_a, &line_b}) {  // every field but the wall times
      line->erase("wall_time");
      line->erase("times");
    }
    EXPECT_EQ(line_a, line_b) << i;
    cut += a[i].at("status") == "cut";
  }
  EXPECT_GT(cut, 0);
  // -j 1 made every run when the search asked; -j 2 made runs ahead on its
  // threads, and the search used one run per evaluation it computed.
  const nlohmann::json ra = tuneResult(dir_ + "/a").at("runs"), rb = tuneResult(dir_ + "/b").at("runs");
  EXPECT_EQ(ra.at("ahead"), 0);
  EXPECT_EQ(ra.at("made"), ra.at("used"));
  EXPECT_EQ(ra.at("cut").get<long>(), cut);  // -j 1: each run stopped at the cut it is judged at
  EXPECT_GT(rb.at("ahead").get<int>(), 0);
  EXPECT_GE(rb.at("made").get<int>(), rb.at("used").get<int>());
  const auto searched = [](const std::vector<nlohmann::json>& all) {
    return std::count_if(all.begin(), all.end(),
                         [](const nlohmann::json& l) { return l.at("phase") != "confirm"; });
  };
  EXPECT_EQ(ra.at("used").get<long>(), searched(a));
  EXPECT_EQ(rb.at("used").get<long>(), searched(b));

  // --full-runs: nothing cut, and the global phase (judged to the end either
  // way) the same, line for line, as the tune with the cut.
  ASSERT_EQ(tune(dir_ + "/full", "--evaluations 20 --global 8 --seed 5 --full-runs", 2).exit_code, 0);
  const std::vector<nlohmann::json> full = tuneLines(dir_ + "/full");
  EXPECT_TRUE(tuneJson(dir_ + "/full").at("arguments").at("cut").is_null());
  EXPECT_EQ(tuneJson(dir_ + "/a").at("arguments").at("cut"), 1.0);
  for (size_t i = 0; i < full.size(); ++i) {
    EXPECT_NE(full[i].at("status"), "cut") << i;
    if (i < a.size() && full[i].at("phase") != "local" && full[i].at("phase") != "confirm") {
      EXPECT_EQ(full[i].at("value"), a[i].at("value")) << i;
    }
  }
}

// What a tune on Slurm refuses before anything is submitted (no cluster
// needed: each refusal comes before sbatch): its options without --slurm, a
// seed range past the largest seed, a folder of the other kind of tune, and
// options given with `collect`.
TEST_F(Tune, SlurmOptionsAndFoldersOfTheOtherKindAreRefusedNamingWhatWasWrong) {
  const auto refused = [](const RunResult& r, const std::string& named) {
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
  };
  refused(tune(dir_ + "/a", "--starts 3"), "--starts is an option of a tune on Slurm");
  refused(tune(dir_ + "/a", "--partition short"), "--partition is an option of a tune on Slurm");
  refused(tune(dir_ + "/a", "--slurm --seed 4294967295 --starts 2"),
          "the last start's seed, seed + starts - 1, is over 4294967295");
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/a/starts.json"));

  // A local tune's folder is not resumed on Slurm, nor a Slurm tune's here.
  ASSERT_EQ(tune(dir_ + "/local", "--evaluations 1 -q").exit_code, 0);
  refused(tune(dir_ + "/local", "--slurm --starts 2"), "holds a tune run here, not on Slurm");
  std::filesystem::create_directories(dir_ + "/onslurm");
  std::ofstream(dir_ + "/onslurm/starts.json") << "{}";
  refused(tune(dir_ + "/onslurm", "--evaluations 1"), "holds a tune on Slurm (starts.json)");
  refused(lagrange("tune collect " + quote(dir_ + "/local")), "holds no Slurm tune (no starts.json)");
  refused(lagrange("tune --slurm collect " + quote(dir_ + "/onslurm")),
          "expected only `lagrange tune collect DIR`");
  refused(lagrange("tune collect " + quote(dir_ + "/onslurm")), "is not a Slurm tune's starts.json");
  // A Slurm tune from before the cut (no full_runs): its starts judged every
  // run to its end, so it is rerun only with --full-runs.
  std::filesystem::create_directories(dir_ + "/older");
  std::ofstream(dir_ + "/older/starts.json")
      << R"({"arguments": {"scenario": ")" << kScenario
      << R"(", "overrides": [], "seed": 1, "span": 2.0, "global": 0, "require_condition": false,)"
      << R"( "starts": 2, "evaluations": 4, "minutes": 0.0}, "job": null})";
  refused(tune(dir_ + "/older", "--slurm --starts 2 --evaluations 4"),
          "holds a Slurm tune of an older lagrange");
  refused(tune(dir_ + "/older", "--slurm --starts 2 --evaluations 4"), "expected --full-runs to resume it");
}

}  // namespace
}  // namespace lagrange::testing
