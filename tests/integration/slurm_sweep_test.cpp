// `lagrange sweep --slurm` against a real one-node Slurm cluster from
// Debian's packages (support/slurm_cluster.hpp): the shards run as a job array, sbatch's options
// pass through, and the table -- waited for, or collected after --no-wait --
// is the one a local sweep writes.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/slurm_cluster.hpp"
#include "support/sweep_files.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

class SlurmSweep : public SlurmClusterTest {};

TEST_F(SlurmSweep, RunsAsAJobArrayAndGivesTheTableALocalSweepGives) {
  const std::string dir = dir_;
  const std::string sweep = dir + "/sweep.yaml";
  std::ofstream(sweep) << "scenario: " << kConfigs << "/rigid_2dof.yaml\nset: {duration: 1}\nseed: 2\naxes:\n"
                       << "  - {key: controller.kd, values: [5, 20]}\n"
                       << "  - {key: initial_state.q, norm: {from: 0.1, to: 10, count: 3, scale: log}}\n";
  ASSERT_EQ(lagrange("sweep " + quote(sweep) + " -o " + quote(dir + "/local") + " -q").exit_code, 0);

  // Waited for: three array tasks, each its share of the rows, in the
  // partition and with the time limit asked for.
  const RunResult waited = lagrange("sweep " + quote(sweep) + " -o " + quote(dir + "/waited") +
                                    " --slurm --shards 3 --partition test --time 10");
  ASSERT_EQ(waited.exit_code, 0) << waited.output << readText(dir + "/cluster/slurmctld.log");
  EXPECT_NE(waited.output.find("submitted Slurm job"), std::string::npos) << waited.output;
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(readText(dir + "/waited/slurm/shard-" + std::to_string(k) + ".out"),
              "shard " + std::to_string(k) + " of 3: ran 2 runs\n");
  const std::string job = readText(dir + "/waited/slurm/sbatch.out")
                              .substr(0, readText(dir + "/waited/slurm/sbatch.out").find('\n'));
  const RunResult shown = shell("scontrol show job " + job);
  EXPECT_NE(shown.output.find("Partition=test"), std::string::npos) << shown.output;
  EXPECT_NE(shown.output.find("TimeLimit=00:10:00"), std::string::npos) << shown.output;
  EXPECT_EQ(tableWithoutWallTime(dir + "/waited"), tableWithoutWallTime(dir + "/local"));

  // Not waited for: submitted, then collected once the job has left the queue.
  const RunResult submitted =
      lagrange("sweep " + quote(sweep) + " -o " + quote(dir + "/later") + " --slurm --no-wait");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  EXPECT_NE(submitted.output.find("lagrange sweep collect"), std::string::npos) << submitted.output;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!shell("squeue -h -o %i").output.empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const RunResult collected = lagrange("sweep collect " + quote(dir + "/later"));
  ASSERT_EQ(collected.exit_code, 0) << collected.output;
  EXPECT_NE(collected.output.find("6 of 6 runs"), std::string::npos) << collected.output;
  EXPECT_EQ(tableWithoutWallTime(dir + "/later"), tableWithoutWallTime(dir + "/local"));
  EXPECT_EQ(fs::exists(dir + "/later/slurm/shard-5.out"), true) << "six rows, six tasks by default";
}

}  // namespace
}  // namespace lagrange::testing
