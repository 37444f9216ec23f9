// End-to-end tests of `lagrange run` on the default scenario (rigid_2dof):
// real processes over LCM in a private network namespace (tests/in_netns.sh).
// Its outputs are checked, and the lockstep trajectory is cross-checked
// against references written independently of the ODE plant; the realtime
// wiring converges like lockstep.
#include <gtest/gtest.h>
#include <lcm/lcm.h>
#include <sched.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "config/scenario.hpp"
#include "controller/cascaded.hpp"
#include "controller/paper_section.hpp"
#include "controller/theorem1.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "logger/tracking_metrics.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/rk4.hpp"
#include "support/run_log.hpp"
#include "support/signal_run.hpp"
#include "transport/checksum.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

// One lockstep run of the default scenario, shared by the cross-checks.
class DefaultRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = freshDir("default");
    result_ = runScenario(kConfigs + "/rigid_2dof.yaml", dir_);
  }
  static std::string dir_;
  static RunResult result_;
};
std::string DefaultRun::dir_;
RunResult DefaultRun::result_;

TEST_F(DefaultRun, ConvergesAndLeavesEveryOutput) {
  ASSERT_EQ(result_.exit_code, 0) << result_.output;
  for (const char* f : {"run.lcm", "config.resolved.yaml", "summary.json"})
    EXPECT_TRUE(fs::exists(fs::path(dir_) / f)) << f;
  const auto j = readSummary(dir_);
  EXPECT_EQ(j["status"], "completed");
  EXPECT_TRUE(j["gains"]["condition_holds"].get<bool>());
  EXPECT_GT(j["gains"]["margin"].get<double>(), 0.0);
  ASSERT_FALSE(j["tracking"]["convergence_time"].is_null());
  EXPECT_LE(j["tracking"]["convergence_time"].get<double>(), 5.0);
  EXPECT_LT(j["tracking"]["final_error"].get<double>(), 1e-3);
  EXPECT_NE(result_.output.find("gain condition eq. (12) HOLDS"), std::string::npos);
  // The log is complete: every tick's truth, the scenario first.
  const auto channels = readChannels(dir_ + "/run.lcm");
  ASSERT_FALSE(channels.empty());
  EXPECT_EQ(channels.front(), "SCENARIO");
  // LCM's self-test is not recorded: its uncounted dispatch used to cost the
  // log the run's first sample (see logger/main.cpp).
  EXPECT_EQ(std::count(channels.begin(), channels.end(), "LCM_SELF_TEST"), 0);
  EXPECT_EQ(readTruth(dir_ + "/run.lcm").size(), 10001u);
  EXPECT_EQ(j["messages"]["PLANT_POSITION"]["rejected"], 0);
  // The logger gave way to the three processes on the tick's path (lockstep.logger_nice: 5).
  EXPECT_EQ(j["timing"]["logger_nice"], std::max(5, getpriority(PRIO_PROCESS, 0)));
  // Every tick's command reached both of its subscribers, the actuator and the
  // logger. Copies are counted, and the controller publishes one per tick plus
  // one per position the plant re-sent; a lost copy is sent again by that same
  // protocol, so counts may miss a copy (seen once in CI: 10002 of 10003) but
  // never a tick.
  const long long published = j["processes"]["controller"]["channels"]["CONTROL_COMMAND"]["published"];
  for (const char* p : {"actuator", "logger"}) {
    const long long received = j["processes"][p]["channels"]["CONTROL_COMMAND"]["received"];
    EXPECT_GE(received, 10001) << p;
    EXPECT_LE(received, published) << p;
  }
  std::set<long long> answered;
  for (const auto& [channel, tick] : readTicks(dir_ + "/run.lcm"))
    if (channel == "ACTUATOR_STATE") answered.insert(tick);
  EXPECT_EQ(answered.size(), 10001u) << "ticks the actuator answered";
}

// lockstep.logger_nice: the logger runs at the nice value the key asks for
// (or the one it inherited, if higher), and says so in summary.json.
TEST(LockstepLogger, RunsAtTheNiceValueOfTheKey) {
  const int own = getpriority(PRIO_PROCESS, 0);
  for (const int nice : {0, 12}) {
    const std::string dir = freshDir("logger_nice_" + std::to_string(nice));
    const RunResult r = runScenario(kConfigs + "/rigid_2dof.yaml", dir,
                                    "--set duration=0.2 --set lockstep.logger_nice=" + std::to_string(nice));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(readSummary(dir)["timing"]["logger_nice"], std::max(nice, own)) << nice;
  }
}

// (a) The analytic model integrated by RK4 under the same sampled controller
// (zero-order hold at the controller rate) stays within 1e-3 rad of the run.
TEST_F(DefaultRun, MatchesRk4OfTheAnalyticModelUnderTheSampledController) {
  ASSERT_EQ(result_.exit_code, 0) << result_.output;
  const config::Scenario s = config::loadScenario(dir_ + "/config.resolved.yaml");
  const model::PlanarChain chain(s.robot);
  const model::Reference reference(s.reference);
  controller::Theorem1Controller ctl(chain, reference, controller::paperSettings(s).gains,
                                     controller::paperSettings(s).initial_filter_state);
  const auto truth = readTruth(dir_ + "/run.lcm");
  const int n = s.dof();
  Eigen::VectorXd x(2 * n);
  x << s.initial_state.q, s.initial_state.qdot;
  const double period = s.tickPeriod();
  // Walk the ticks, not the samples: the comparison survives a sample the
  // logger did not record (seen once: PLANT_TRUTH of tick 0 lost, #7).
  std::map<long long, Eigen::VectorXd> recorded;
  for (const TruthSample& sample : truth) recorded[sample.tick] = sample.q;
  double worst = 0.0;
  for (long long k = 0; k <= s.lastTick(); ++k) {
    if (const auto it = recorded.find(k); it != recorded.end())
      worst = std::max(worst, (it->second - x.head(n)).cwiseAbs().maxCoeff());
    const Eigen::VectorXd u = ctl.step(static_cast<double>(k) * period, x.head(n)).u;
    for (int i = 0; i < 10; ++i) x = armStep(chain, x, u, period / 10);
  }
  std::printf("lockstep vs RK4 (sampled controller): max |dq| = %.3e rad over %zu of %lld samples\n", worst,
              recorded.size(), s.lastTick() + 1);
  EXPECT_GT(recorded.size(), static_cast<size_t>(s.lastTick()) * 99 / 100);
  EXPECT_LT(worst, 1e-3);
}

// (b) The continuous-time closed loop of eqs. (10) and (90): the convergence
// time agrees with the lockstep run's within 5 %.
TEST_F(DefaultRun, ConvergenceTimeMatchesTheContinuousClosedLoop) {
  ASSERT_EQ(result_.exit_code, 0) << result_.output;
  const config::Scenario s = config::loadScenario(dir_ + "/config.resolved.yaml");
  const model::PlanarChain chain(s.robot);
  const model::Reference reference(s.reference);
  const auto& g = controller::paperSettings(s).gains;
  const int n = s.dof();
  // State [q; q'; qc], qc(0) bumpless as in the run.
  Eigen::VectorXd x(3 * n);
  const Eigen::VectorXd qt0 = s.initial_state.q - reference.evaluate(0.0).q();
  x << s.initial_state.q, s.initial_state.qdot,
      controller::paperSettings(s).initial_filter_state.value_or(-g.b.cwiseProduct(qt0));
  auto f = [&](double t, const Eigen::VectorXd& st) {
    const model::ReferenceSample r = reference.evaluate(t);
    const Eigen::VectorXd q = st.head(n), v = st.segment(n, n), qc = st.tail(n);
    const Eigen::VectorXd qt = q - r.q();
    const Eigen::VectorXd theta = qc + g.b.cwiseProduct(qt);
    const Eigen::VectorXd u = -g.kp.cwiseProduct(qt) - g.kd.cwiseProduct(theta) + chain.inertia(q) * r.qdd() +
                              chain.coriolis(q, r.qd()) * r.qd() + chain.gravity(q);
    Eigen::VectorXd d(3 * n);
    d << v, chain.acceleration(q, v, u), -g.a.cwiseProduct(theta);
    return d;
  };
  logger::TrackingMetrics metrics(reference, s.metrics.tolerance);
  const double h = 1e-4;
  for (long long k = 0; k <= s.lastTick(); ++k) {
    const double t = k * s.tickPeriod();
    metrics.addSample(k, t, x.head(n));
    for (int i = 0; i < 10; ++i) x = rk4Step(f, t + i * h, x, h);
  }
  const auto continuous = metrics.summary().convergence_time;
  const auto j = readSummary(dir_);
  ASSERT_TRUE(continuous.has_value());
  const double lockstep = j["tracking"]["convergence_time"].get<double>();
  std::printf("convergence time: lockstep %.4f s, continuous-time closed loop %.4f s\n", lockstep,
              *continuous);
  EXPECT_NEAR(lockstep, *continuous, 0.05 * *continuous);
}

TEST_F(DefaultRun, LockstepRunsAreDeterministic) {
  ASSERT_EQ(result_.exit_code, 0) << result_.output;
  const std::string dir = freshDir("repeat");
  const RunResult again = runScenario(kConfigs + "/rigid_2dof.yaml", dir, "--set duration=3 -q");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  const auto a = readTruth(dir_ + "/run.lcm"), b = readTruth(dir + "/run.lcm");
  const size_t common = forCommonTicks(a, b, [](const TruthSample& x, const TruthSample& y) {
    ASSERT_EQ(x.q, y.q) << "tick " << x.tick;  // bit for bit
    ASSERT_EQ(x.qdot, y.qdot) << "tick " << x.tick;
  });
  EXPECT_EQ(b.size(), 3001u);
  EXPECT_EQ(common, 3001u);
}

// Realtime: the same scenario on fixed-rate loops converges like lockstep,
// and reports its timing. (Timing numbers are benchmarks, not asserted.)
TEST_F(DefaultRun, RealtimeConvergesLikeLockstepAndReportsTiming) {
  ASSERT_EQ(result_.exit_code, 0) << result_.output;
  const std::string dir = freshDir("realtime");
  // 3 s of wall time, not the config's 10: the lockstep run converges at 0.9 s, and `met`
  // then asks the error to stay below the tolerance to the end, 3 s.
  const RunResult r = runScenario(kConfigs + "/rigid_2dof.yaml", dir, "-q --mode realtime --set duration=3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(dir), lockstep = readSummary(dir_);
  EXPECT_EQ(j["mode"], "realtime");
  EXPECT_EQ(j["tracking"]["tolerance"], lockstep["tracking"]["tolerance"]);
  ASSERT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  const double t_rt = j["tracking"]["convergence_time"], t_ls = lockstep["tracking"]["convergence_time"];
  std::printf("convergence time: realtime %.4f s, lockstep %.4f s\n", t_rt, t_ls);
  EXPECT_NEAR(t_rt, t_ls, 0.10 * t_ls);
  for (const char* p : {"plant", "controller", "actuator"}) {
    const auto& loop = j["timing"]["loops"][p];
    EXPECT_GT(loop["cycles"].get<long long>(), 2700) << p;
    for (const char* key : {"achieved_rate", "deadline_misses", "longest_miss_run", "on_time_fraction"})
      EXPECT_TRUE(loop.contains(key)) << p << " " << key;
    EXPECT_LE(loop["jitter"]["p50"].get<double>(), loop["jitter"]["max"].get<double>());
  }
  EXPECT_GT(j["timing"]["latency"]["p50"].get<double>(), 0.0);
  EXPECT_TRUE(j["messages"]["stale"]["plant"].contains("torque_zeroed"));
}

// realtime.cpus keeps a process on the CPUs it names: each loop reports the
// CPUs it ran on. A CPU the machine does not have is refused before anything
// starts, naming the key and the machine's CPUs.
TEST(RealtimeCpus, PinEachProcessWhereTheKeySaysAndRefuseACpuTheMachineLacks) {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  if (!CPU_ISSET(0, &allowed) || !CPU_ISSET(1, &allowed))
    GTEST_SKIP() << "CPUs 0 and 1 are not both ours to pin";
  const std::string dir = freshDir("realtime-cpus");
  const RunResult r = runScenario(kConfigs + "/rigid_2dof.yaml", dir,
                                  "-q --mode realtime --set duration=0.5 --set "
                                  "'realtime.cpus={plant: [0], controller: [1]}'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto loops = readSummary(dir)["timing"]["loops"];
  const auto scheduler = [&](const char* p) { return loops[p]["scheduler"].get<std::string>(); };
  EXPECT_NE(scheduler("plant").find(" cpus 0"), std::string::npos) << scheduler("plant");
  EXPECT_NE(scheduler("controller").find(" cpus 1"), std::string::npos) << scheduler("controller");
  EXPECT_EQ(scheduler("actuator").find("cpus"), std::string::npos) << "not named: anywhere";

  const std::string bad = freshDir("realtime-cpus-bad");
  const RunResult refused = runScenario(kConfigs + "/rigid_2dof.yaml", bad,
                                        "--mode realtime --set 'realtime.cpus={actuator: [1023]}'");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("realtime.cpus.actuator: CPU 1023 is not among this machine's CPUs 0-"),
            std::string::npos)
      << refused.output;
  EXPECT_FALSE(std::filesystem::exists(bad + "/run.lcm")) << "nothing was started";
}

}  // namespace
}  // namespace lagrange::testing
