#pragma once
/// @file
/// A fixture with a real one-node Slurm cluster from Debian's packages
/// (tests/integration/slurm_cluster.sh starts munge, slurmctld and slurmd
/// inside the test's private network namespace, and stops them after the
/// suite). SLURM_CONF points the clients (sbatch, squeue, scontrol) at it.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <string>

#include "support/launch.hpp"

namespace lagrange::testing {

class SlurmClusterTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = freshDir("slurm");
    const RunResult r = shell(script() + " start " + quote(dir_ + "/cluster"));
    started_ = r.exit_code == 0;
    start_output_ = r.output;
    setenv("SLURM_CONF", (dir_ + "/cluster/slurm.conf").c_str(), 1);
  }
  static void TearDownTestSuite() { shell(script() + " stop " + quote(dir_ + "/cluster")); }
  void SetUp() override { ASSERT_TRUE(started_) << "the test cluster did not start:\n" << start_output_; }

  static std::string script() {
    return std::string(LAGRANGE_SOURCE_DIR) + "/tests/integration/slurm_cluster.sh";
  }

  static inline std::string dir_;  ///< the suite's folder; the cluster's files in dir_/cluster
  static inline std::string start_output_;
  static inline bool started_ = false;
};

}  // namespace lagrange::testing
