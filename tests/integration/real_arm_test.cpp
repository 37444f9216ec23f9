// The real arm's joints in whole runs (#30): what damping and friction take
// is what the log's energies lose; the URDF's efforts bound every torque; its
// joint limits hold the arm. In-process runs (the physics is the same in
// every wiring: plant::plantFor builds it for all).
#include <gtest/gtest.h>

#include <cmath>

#include "config/scenario.hpp"
#include "model/urdf_arm.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

const std::string kPanda = kConfigs + "/panda_theorem1.yaml";

TEST(RealArm, ALossyArmsLoggedEnergyFallsByWhatItsDampingAndFrictionTake) {
  // The default scenario's arm with damping and friction, tracked for 2 s.
  const std::string dir = freshDir("energy-balance");
  const std::string losses =
      " --set 'plant.joint_damping=[0.8, 0.2]' --set 'plant.joint_friction=[1.5, 0.4]'";
  const RunResult r = runScenario(kRigid, dir, "-q --mode inproc --set duration=2" + losses);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<TruthSample> truth = readTruth(dir + "/run.lcm");
  ASSERT_EQ(truth.size(), 2001u);
  const Eigen::Vector2d damping(0.8, 0.2), friction(1.5, 0.4);
  // Over [0.2 s, 2 s], after the start's fast transient (where ODE's own
  // energy error, ~0.1 J at this step, builds up while the links turn at
  // tens of rad/s). Each period's torque is held flat (one actuator step a
  // period), so its work is tau . (q(k) - q(k-1)) exactly; the losses' power
  // D q'^2 + F |q'| is integrated by the trapezoid rule over the 1 ms samples.
  auto balance = [](const std::vector<TruthSample>& run, const Eigen::Vector2d& d, const Eigen::Vector2d& f) {
    struct {
      double change, work, lost;
    } b{run.back().energy - run[200].energy, 0.0, 0.0};
    auto power = [&](const Eigen::VectorXd& v) {
      return (d.cwiseProduct(v.cwiseAbs2()) + f.cwiseProduct(v.cwiseAbs())).sum();
    };
    for (size_t k = 201; k < run.size(); ++k) {
      b.work += run[k].tau.dot(run[k].q - run[k - 1].q);
      b.lost += 0.5 * (power(run[k].qdot) + power(run[k - 1].qdot)) * (run[k].t - run[k - 1].t);
    }
    return b;
  };
  const auto lossy = balance(truth, damping, friction);
  RecordProperty("work", std::to_string(lossy.work));
  RecordProperty("lost", std::to_string(lossy.lost));
  ASSERT_GT(lossy.lost, 1.0);  // the losses took something worth checking
  // E(T) - E(0.2) = work - losses, to within the trapezoid's and ODE's error.
  EXPECT_NEAR(lossy.change, lossy.work - lossy.lost, 0.01 * lossy.lost)
      << "change " << lossy.change << ", work " << lossy.work << ", lost " << lossy.lost;
  // Without the losses the same balance has nothing to take: the check can tell.
  const std::string lossless = freshDir("energy-balance-lossless");
  ASSERT_EQ(runScenario(kRigid, lossless, "-q --mode inproc --set duration=2").exit_code, 0);
  const auto ideal =
      balance(readTruth(lossless + "/run.lcm"), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  EXPECT_NEAR(ideal.change, ideal.work, 0.01 * lossy.lost)
      << "change " << ideal.change << ", work " << ideal.work;
}

// The largest angle of panda_joint4 (upper limit -0.0698) in a Panda run
// started at -0.1 rad on it, turning at 4 rad/s towards the limit.
double highestElbowAngle(bool joint_limits) {
  const std::string dir = freshDir("panda-stop");
  const RunResult r =
      runScenario(kPanda, dir,
                  std::string("-q --mode inproc --set duration=0.3 --set plant.joint_limits=") +
                      (joint_limits ? "true" : "false") +
                      " --set 'initial_state.q=[0.5, -0.3, -0.4, -0.1, 0.4, 0.6, 1.2]'"
                      " --set 'initial_state.qdot=[0, 0, 0, 4, 0, 0, 0]'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  double highest = -10.0;
  for (const TruthSample& sample : readTruth(dir + "/run.lcm")) highest = std::max(highest, sample.q(3));
  return highest;
}

TEST(RealArm, TheUrdfsJointLimitsStopTheJoint) {
  const double upper = -0.0698;  // robots/panda.urdf, panda_joint4
  const double free = highestElbowAngle(false), stopped = highestElbowAngle(true);
  EXPECT_GT(free, upper + 0.02);  // without the stop the elbow overshoots its limit
  EXPECT_LE(stopped, upper + 0.005);
  EXPECT_GT(stopped, upper - 0.005);  // and with it, it reaches the stop and stays there
}

TEST(RealArm, TheUrdfsEffortLimitsBoundEveryTorque) {
  const std::string dir = freshDir("panda-limits");
  const RunResult r =
      runScenario(kPanda, dir, "-q --mode inproc --set duration=0.5 --set actuator.saturation=urdf");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const config::Scenario s = config::loadScenario(kPanda);
  const auto& joints = s.urdf_model->jointProperties();
  const std::vector<TruthSample> truth = readTruth(dir + "/run.lcm");
  ASSERT_EQ(truth.size(), 501u);
  std::vector<int> at_limit(joints.size(), 0);
  for (const TruthSample& sample : truth)
    for (size_t i = 0; i < joints.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      EXPECT_LE(std::abs(sample.tau(k)), *joints[i].effort) << "joint " << i << " at t = " << sample.t;
      if (std::abs(sample.tau(k)) == *joints[i].effort) ++at_limit[i];
    }
  // The shipped Panda's gains ask for more than 12 N m on the wrist: it was clipped.
  EXPECT_GT(at_limit[6], 0);
}

}  // namespace
}  // namespace lagrange::testing
