// The controller seam: test_pd, defined and registered only in
// tests/support/test_pd_controller.cpp, runs in the in-process and lockstep
// wirings with no edit outside tests/ -- through the project's own mains,
// built with that file linked in (bin-test-controller/).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "config/scenario.hpp"
#include "model/planar_chain.hpp"
#include "model/reference.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

const std::string kSeamBin = LAGRANGE_SEAM_BIN_DIR;

constexpr const char* kConfig = R"(name: test_pd_seam
duration: 2.0
mode: lockstep
robot:
  preset: pelican
initial_state:
  q: [0.5, -0.5]
  qdot: [0.0, 0.0]
reference:
  type: smooth_sine
  offset: [0.7853981633974483, 1.0471975511965976]
  amplitude: [0.3490658503988659, 0.5235987755982988]
  frequency: [4.0, 3.0]
  alpha: [2.0, 1.8]
plant:
  physics_step: 1.0e-4
  publish_rate: 1000
controller:
  type: test_pd
  kp: [150.0, 10.0]
  kd: [15.0, 1.0]
)";

std::string writeConfig() {
  const std::string path = freshDir("seam-config") + ".yaml";
  std::ofstream(path) << kConfig;
  return path;
}

TEST(ControllerSeam, TheStockProgramsDoNotKnowTheTestController) {
  const RunResult r = lagrange("check-gains " + quote(writeConfig()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  // The paper's and the baselines' types are offered; the test's is not.
  EXPECT_NE(r.output.find("unknown controller type 'test_pd'; expected: theorem1, cascaded, flexible, "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("pd_plus_differenced"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("test_pd,"), std::string::npos) << r.output;
}

TEST(ControllerSeam, ATestOnlyControllerRunsInProcessAndInLockstepBitForBit) {
  const std::string config = writeConfig();
  const std::string lockstep = freshDir("seam-lockstep"), inproc = freshDir("seam-inproc");
  const auto run = [&](const std::string& out, const std::string& mode) {
    return shell(kSeamBin + "/lagrange run " + quote(config) + " --out " + quote(out) + " -q --mode " + mode);
  };
  const RunResult a = run(lockstep, "lockstep"), b = run(inproc, "inproc");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;

  // Every tick in both, the same trajectory and the same commands bit for bit.
  const auto ta = readTruth(lockstep + "/run.lcm"), tb = readTruth(inproc + "/run.lcm");
  ASSERT_EQ(ta.size(), 2001u);
  ASSERT_EQ(tb.size(), 2001u);
  for (size_t k = 0; k < ta.size(); ++k) {
    ASSERT_EQ(ta[k].q, tb[k].q) << "tick " << k;
    ASSERT_EQ(ta[k].qdot, tb[k].qdot) << "tick " << k;
  }
  const auto ca = readCommands(lockstep + "/run.lcm"), cb = readCommands(inproc + "/run.lcm");
  ASSERT_EQ(ca.size(), 2001u);
  ASSERT_EQ(ca, cb);

  // The commands are test_pd's law (so it, not a paper controller, ran):
  // g(q) - kp (q - q_d) - kd (q_k - q_{k-1}) / T.
  const config::Scenario s = config::loadScenario(config, {});
  const model::PlanarChain arm(s.robot);
  const model::Reference reference(s.reference);
  const Eigen::Vector2d kp(150.0, 10.0), kd(15.0, 1.0);
  for (size_t k = 0; k < ta.size(); ++k) {
    const Eigen::VectorXd& q = ta[k].q;
    const Eigen::VectorXd rate =
        k == 0 ? Eigen::VectorXd::Zero(2) : Eigen::VectorXd((q - ta[k - 1].q) / (ta[k].t - ta[k - 1].t));
    const Eigen::VectorXd expected =
        arm.gravity(q) - kp.cwiseProduct(q - reference.evaluate(ta[k].t, 0).q()) - kd.cwiseProduct(rate);
    const Eigen::VectorXd u = transport::toEigen(ca.at(static_cast<long long>(k)));
    ASSERT_LT((u - expected).norm(), 1e-9 * (1.0 + expected.norm())) << "tick " << k;
  }

  // Its keys in summary.json and config.resolved.yaml; its gains unchecked, and said.
  const auto j = readSummary(lockstep);
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["controller"]["type"], "test_pd");
  EXPECT_EQ(j["controller"]["kp"], nlohmann::json({150.0, 10.0}));
  EXPECT_FALSE(j["gains"]["checked"].get<bool>());
  EXPECT_NE(j["gains"]["why"].get<std::string>().find("test_pd"), std::string::npos);
  const RunResult resolved =
      shell(kSeamBin + "/lagrange check-gains " + quote(lockstep + "/config.resolved.yaml"));
  EXPECT_EQ(resolved.exit_code, 1) << resolved.output;  // loads; nothing to hold
  EXPECT_NE(resolved.output.find("gain conditions NOT CHECKED"), std::string::npos) << resolved.output;
}

}  // namespace
}  // namespace lagrange::testing
