// The joint-angle sensor in the plant's measurement path (sensors.*): the
// controller sees the readings -- quantised, noisy, a sample late -- while
// PLANT_TRUTH keeps the true angles; lockstep and in-process compute the
// same run bit for bit with the noise on, and the log replays exactly through
// every component (the plant draws the same noise again).
#include <gtest/gtest.h>

#include <cmath>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

constexpr double kCounts = 4096, kSigma = 1e-4;
const std::string kSensors =
    "--set duration=3 --set 'sensors={seed: 3, position: {counts_per_revolution: 4096, "
    "noise_sigma: 1.0e-4, delay: 1}}'";

TEST(Sensors, ReadingsAreQuantisedNoisyAndLateAndEveryWiringAgrees) {
  const std::string config = kConfigs + "/rigid_2dof.yaml";
  const std::string lockstep = freshDir("sensors-lockstep"), inproc = freshDir("sensors-inproc");
  ASSERT_EQ(runScenario(config, lockstep, "-q --mode lockstep " + kSensors).exit_code, 0);
  ASSERT_EQ(runScenario(config, inproc, "-q --mode inproc " + kSensors).exit_code, 0);

  const auto truth = readTruth(lockstep + "/run.lcm");
  const auto read = readPositions(lockstep + "/run.lcm");
  ASSERT_EQ(truth.size(), 3001u);
  ASSERT_EQ(read.size(), 3001u);
  // The sensor acted: every reading is a whole number of counts, within a
  // count and a few sigma below the angle of the tick before, and most differ
  // from the true angle of their own tick.
  const double step = 2 * M_PI / kCounts;
  size_t differs = 0;
  for (size_t k = 1; k < truth.size(); ++k) {
    const std::vector<double>& q = read.at(static_cast<long long>(k));
    for (size_t j = 0; j < q.size(); ++j) {
      EXPECT_NEAR(q[j] / step, std::round(q[j] / step), 1e-6) << "tick " << k;
      const double late = truth[k - 1].q(static_cast<Eigen::Index>(j));
      EXPECT_LE(q[j], late + 6 * kSigma) << "tick " << k;
      EXPECT_GE(q[j], late - step - 6 * kSigma) << "tick " << k;
      differs += q[j] != truth[k].q(static_cast<Eigen::Index>(j));
    }
  }
  EXPECT_GT(differs, 5900u);
  // The controller still brings the true angles within a few counts.
  const auto j = readSummary(lockstep);
  EXPECT_LT(j["tracking"]["final_error"].get<double>(), 3 * step) << j["tracking"].dump();

  // In-process: the same readings, trajectory and commands, bit for bit.
  const auto truth_inproc = readTruth(inproc + "/run.lcm");
  ASSERT_EQ(truth_inproc.size(), truth.size());
  for (size_t k = 0; k < truth.size(); ++k) ASSERT_EQ(truth[k].q, truth_inproc[k].q) << "tick " << k;
  EXPECT_EQ(read, readPositions(inproc + "/run.lcm"));
  EXPECT_EQ(readCommands(lockstep + "/run.lcm"), readCommands(inproc + "/run.lcm"));

  for (const std::string component : {"controller", "actuator", "plant"}) {
    const RunResult replay = lagrange("replay " + quote(lockstep + "/run.lcm") + " --component " + component);
    EXPECT_EQ(replay.exit_code, 0) << component << ": " << replay.output;
    EXPECT_NE(replay.output.find("reproduced all 3001 recorded outputs"), std::string::npos) << replay.output;
  }
}

}  // namespace
}  // namespace lagrange::testing
