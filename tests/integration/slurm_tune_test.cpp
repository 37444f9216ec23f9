// `lagrange tune --slurm` against a real one-node Slurm cluster
// (support/slurm_cluster.hpp): each start is an array task whose evaluations
// are those of a local tune with its seed, the result is the best of them,
// a rerun submits nothing once every start has finished, and `tune collect`
// says which start is not finished and refuses a start folder of another tune.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "support/configs.hpp"
#include "support/help_examples.hpp"
#include "support/launch.hpp"
#include "support/slurm_cluster.hpp"
#include "support/tune_files.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// The 2-joint arm with short runs (as tune_test.cpp's) and a budget of
// seconds; a span of 0.3 decades, where seeds 3 and 4 find different bests.
std::string tuneCommand() {
  return "tune " + kConfigs +
         "/rigid_2dof.yaml --set duration=2 --set plant.physics_step=1e-4 "
         "--set metrics.convergence_deadline=1.5 --evaluations 8 --global 6 --span 0.3 -q "
         // A value the job script must quote: spaces, quotes, a $.
         "--set \"description=a b \\$HOME 'q'\" ";
}

// What the search found, not what the machine took.
std::vector<nlohmann::json> evaluations(const std::string& dir) {
  std::vector<nlohmann::json> out = tuneLines(dir);
  for (nlohmann::json& line : out) {
    line.erase("wall_time");
    line.erase("times");
  }
  return out;
}

class SlurmTune : public SlurmClusterTest {};

TEST_F(SlurmTune, EachStartIsTheLocalTuneOfItsSeedAndTheBestOfThemIsKept) {
  const std::string work = dir_ + "/work";
  fs::create_directories(work + "/runs");
  for (const unsigned seed : {3u, 4u})
    ASSERT_EQ(lagrange(tuneCommand() + "--seed " + std::to_string(seed) + " --out " +
                       quote(dir_ + "/local-" + std::to_string(seed)))
                  .exit_code,
              0);

  const std::string out = work + "/runs/tuned";
  const std::string slurm =
      tuneCommand() + "--seed 3 --out " + quote(out) + " --slurm --starts 2 --partition test --time 10";
  const RunResult waited = lagrange(slurm);
  ASSERT_EQ(waited.exit_code, 0) << waited.output << readText(dir_ + "/cluster/slurmctld.log");
  const std::string sbatch = readText(out + "/slurm/sbatch.out");
  const std::string job = sbatch.substr(0, sbatch.find('\n'));
  const RunResult shown = shell("scontrol show job " + job);
  EXPECT_NE(shown.output.find("Partition=test"), std::string::npos) << shown.output;
  EXPECT_NE(shown.output.find("TimeLimit=00:10:00"), std::string::npos) << shown.output;

  // The --set value reached each start as it was typed.
  const nlohmann::json overrides =
      nlohmann::json::parse(std::ifstream(out + "/starts/1/tune.json")).at("arguments").at("overrides");
  EXPECT_NE(std::find(overrides.begin(), overrides.end(), "description=a b $HOME 'q'"), overrides.end())
      << overrides;
  // Start K is the local tune with seed 3 + K, evaluation for evaluation
  // (and the seeds' tunes differ: a start that ignored its seed would fail this).
  ASSERT_NE(evaluations(dir_ + "/local-3"), evaluations(dir_ + "/local-4"));
  for (const int k : {0, 1}) {
    const std::vector<nlohmann::json> start = evaluations(out + "/starts/" + std::to_string(k)),
                                      local = evaluations(dir_ + "/local-" + std::to_string(3 + k));
    ASSERT_GT(start.size(), 3u) << k;
    EXPECT_EQ(start, local) << "start " << k;
  }
  // The result is the faster of the two local tunes' bests (the first on a tie).
  const nlohmann::json a = tuneResult(dir_ + "/local-3").at("best"),
                       b = tuneResult(dir_ + "/local-4").at("best");
  ASSERT_TRUE(a.is_object() && b.is_object()) << a << b;
  const bool second = b.at("convergence_time").get<double>() < a.at("convergence_time").get<double>();
  const nlohmann::json collected = tuneResult(out);
  EXPECT_EQ(collected.at("best_start"), second ? 1 : 0) << collected.dump();
  EXPECT_EQ(collected.at("best").at("gains"), (second ? b : a).at("gains")) << collected.dump();
  EXPECT_EQ(collected.at("missing"), nlohmann::json::array());
  EXPECT_TRUE(fs::exists(out + "/front.png"));
  // tuned.yaml runs as it is and sets the best's gains.
  const RunResult run =
      lagrange("run " + quote(out + "/tuned.yaml") + " --mode inproc -q --out " + quote(dir_ + "/run"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json resolved = nlohmann::json::parse(std::ifstream(dir_ + "/run/config.resolved.json"));
  for (const auto& [name, values] : collected.at("best").at("gains").items()) {
    const nlohmann::json& set = resolved.at("controller").at(name);
    EXPECT_EQ(set.is_array() ? set.get<std::vector<double>>() : std::vector<double>{set.get<double>()},
              values.get<std::vector<double>>())
        << name;
  }

  // The same command again: every start is finished, nothing is submitted.
  const RunResult again = lagrange(slurm);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(readText(out + "/slurm/sbatch.out"), sbatch);
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(out + "/starts.json")).at("job"), job);

  // `tune collect`, as its --help shows it, from the folder the example names.
  const CommandHelp collect = commandHelp("tune collect");
  ASSERT_EQ(collect.examples.size(), 1u) << collect.text;
  const RunResult merged = runExample(collect.examples[0], work);
  EXPECT_EQ(merged.exit_code, 0) << merged.output;
  EXPECT_NE(merged.output.find("the best from start " + std::to_string(second ? 1 : 0)), std::string::npos)
      << merged.output;

  // A start killed midway (its tune.json's result null, as a tune leaves it
  // until its end) is not finished: named, exit 1, and tuned.yaml written
  // anew from the best of the rest.
  const nlohmann::json start_1 = nlohmann::json::parse(std::ifstream(out + "/starts/1/tune.json"));
  std::ofstream(out + "/starts/1/tune.json")
      << nlohmann::json({{"arguments", start_1.at("arguments")}, {"result", nullptr}}).dump();
  fs::remove(out + "/tuned.yaml");
  const RunResult partial = lagrange("tune collect " + quote(out));
  EXPECT_EQ(partial.exit_code, 1) << partial.output;
  EXPECT_NE(partial.output.find("start 1 (seed 4) is not finished: no result in its tune.json"),
            std::string::npos)
      << partial.output;
  EXPECT_EQ(tuneResult(out).at("best_start"), 0);
  EXPECT_EQ(tuneResult(out).at("missing"), nlohmann::json::array({1}));
  EXPECT_EQ(tuneResult(out).at("best").at("gains"), a.at("gains"));
  EXPECT_TRUE(fs::exists(out + "/tuned.yaml"));

  // The same command then submits start 1 alone, which resumes from its
  // tune.jsonl (nothing computed again) to the same result.
  const std::string start_0_out = readText(out + "/slurm/start-0.out");
  const RunResult resumed = lagrange(slurm);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(readText(out + "/slurm/sbatch.out"), sbatch);
  EXPECT_EQ(readText(out + "/slurm/start-0.out"), start_0_out);
  EXPECT_NE(readText(out + "/slurm/start-1.out").find("0 computed"), std::string::npos)
      << readText(out + "/slurm/start-1.out");
  EXPECT_EQ(tuneResult(out).at("best"), collected.at("best"));

  // Not waited for: submitted, then collected once the job has left the queue.
  const std::string later = work + "/runs/later";
  const RunResult submitted =
      lagrange(tuneCommand() + "--seed 3 --out " + quote(later) + " --slurm --starts 2 --no-wait");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  EXPECT_NE(submitted.output.find("has ended: lagrange tune collect"), std::string::npos) << submitted.output;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!shell("squeue -h -o %i").output.empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const RunResult collected_later = lagrange("tune collect " + quote(later));
  EXPECT_EQ(collected_later.exit_code, 0) << collected_later.output;
  EXPECT_EQ(tuneResult(later).at("best"), collected.at("best"));

  // Start 0's tune.json put in start 1's folder: another seed's, refused.
  ASSERT_TRUE(fs::remove(out + "/starts/1/tune.json"));
  fs::copy_file(out + "/starts/0/tune.json", out + "/starts/1/tune.json");
  const RunResult planted = lagrange("tune collect " + quote(out));
  EXPECT_EQ(planted.exit_code, 2) << planted.output;
  EXPECT_NE(planted.output.find("another tune's arguments than start 1's (seed 4)"), std::string::npos)
      << planted.output;
}

}  // namespace
}  // namespace lagrange::testing
