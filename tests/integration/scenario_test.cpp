// End-to-end tests of `lagrange run`: real processes over LCM, in a private
// network namespace (tests/in_netns.sh). Each run's outputs are checked, and
// the lockstep trajectory is cross-checked against references written
// independently of the ODE plant.
#include "config/scenario.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include "controller/cascaded.hpp"
#include "controller/theorem1.hpp"
#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "logger/tracking_metrics.hpp"
#include "support/launch.hpp"
#include "support/rk4.hpp"
#include "support/run_log.hpp"
#include "support/signal_run.hpp"
#include "transport/checksum.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;
const std::string kConfigs = std::string(LAGRANGE_SOURCE_DIR) + "/configs";

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
  EXPECT_NE(result_.output.find("gain condition eq. (11) HOLDS"), std::string::npos);
  // The log is complete: every tick's truth, the scenario first.
  const auto channels = readChannels(dir_ + "/run.lcm");
  ASSERT_FALSE(channels.empty());
  EXPECT_EQ(channels.front(), "SCENARIO");
  // LCM's self-test is not recorded: its uncounted dispatch used to cost the
  // log the run's first sample (see logger/main.cpp).
  EXPECT_EQ(std::count(channels.begin(), channels.end(), "LCM_SELF_TEST"), 0);
  EXPECT_EQ(readTruth(dir_ + "/run.lcm").size(), 10001u);
  EXPECT_EQ(j["messages"]["PLANT_POSITION"]["rejected"], 0);
  // Every command reached both of its subscribers, the actuator and the logger.
  EXPECT_EQ(j["processes"]["actuator"]["channels"]["CONTROL_COMMAND"]["received"],
            j["processes"]["controller"]["channels"]["CONTROL_COMMAND"]["published"]);
  EXPECT_EQ(j["processes"]["logger"]["channels"]["CONTROL_COMMAND"]["received"],
            j["processes"]["controller"]["channels"]["CONTROL_COMMAND"]["published"]);
}

// (a) The analytic model integrated by RK4 under the same sampled controller
// (zero-order hold at the controller rate) stays within 1e-3 rad of the run.
TEST_F(DefaultRun, MatchesRk4OfTheAnalyticModelUnderTheSampledController) {
  ASSERT_EQ(result_.exit_code, 0) << result_.output;
  const config::Scenario s = config::loadScenario(dir_ + "/config.resolved.yaml");
  const model::PlanarChain chain(s.robot);
  const model::Reference reference(s.reference);
  controller::Theorem1Controller ctl(chain, reference, s.controller.gains, s.controller.initial_filter_state);
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
  const auto& g = s.controller.gains;
  const int n = s.dof();
  // State [q; q'; qc], qc(0) bumpless as in the run.
  Eigen::VectorXd x(3 * n);
  const Eigen::VectorXd qt0 = s.initial_state.q - reference.evaluate(0.0).q();
  x << s.initial_state.q, s.initial_state.qdot,
      s.controller.initial_filter_state.value_or(-g.b.cwiseProduct(qt0));
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
  EXPECT_GE(common, 3000u);  // of 3001
}

class ShippedConfig : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedConfig, MeetsItsStatedMetric) {
  const std::string dir = freshDir(GetParam());
  const RunResult r = runScenario(kConfigs + "/" + GetParam() + ".yaml", dir, "-q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(dir);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  if (GetParam().rfind("rigid", 0) == 0) {
    EXPECT_TRUE(j["gains"]["condition_holds"].get<bool>()) << j["gains"].dump();
  } else {
    // Theorems 2 (m = 1) and 3 (m >= 2): evaluated -- and, as the configs
    // explain, far from met; the reference is not a free motion.
    EXPECT_EQ(j["gains"]["conditions"].size(), 4u);
    EXPECT_FALSE(j["gains"]["condition_holds"].get<bool>());
    EXPECT_TRUE(j["gains"].contains("eta"));
    const bool free_motion = GetParam().find("free_motion") != std::string::npos ||
                             GetParam().rfind("flexible", 0) == 0;  // the flexible configs follow (608)
    if (!free_motion)
      EXPECT_NE(j["gains"]["warnings"][0].get<std::string>().find("not a free motion"), std::string::npos);
    else if (GetParam().find("filtered_rate") != std::string::npos)  // outside the Corollary, and said
      EXPECT_NE(j["gains"]["warnings"][0].get<std::string>().find("Corollary assumes"), std::string::npos);
    else
      EXPECT_FALSE(j["gains"].contains("warnings"));
  }
  if (GetParam().rfind("flexible", 0) == 0) {  // the motor side is recorded, and said how q2' was had
    EXPECT_EQ(j["messages"]["PLANT_MOTOR"]["published"], j["messages"]["PLANT_POSITION"]["published"]);
    EXPECT_EQ(j["controller"]["motor_rate"].get<std::string>(),
              GetParam().find("filtered") == std::string::npos ? "measured" : "filtered");
  }
  const auto truth = readTruth(dir + "/run.lcm");
  for (const auto& sample : truth) ASSERT_TRUE(sample.q.allFinite() && sample.qdot.allFinite());
}

INSTANTIATE_TEST_SUITE_P(Configs, ShippedConfig,
                         ::testing::Values("rigid_2dof_large_error", "rigid_5link", "chain_m1", "chain_m2",
                                           "chain_m3", "chain_m1_free_motion", "flexible_1dof",
                                           "flexible_2dof", "flexible_2dof_filtered_rate"));

std::vector<std::string> shippedConfigs() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kConfigs))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Every u the controller published, in tick order (first copy of each tick).
std::map<long long, std::vector<double>> readCommands(const std::string& log_path) {
  lcm::LogFile log(log_path, "r");
  std::map<long long, std::vector<double>> by_tick;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    if (ev->channel != "CONTROL_COMMAND") continue;
    lagrange::control_command_t m;
    if (m.decode(ev->data, 0, ev->datalen) < 0) throw std::runtime_error("bad CONTROL_COMMAND");
    by_tick.emplace(m.header.tick, m.u);
  }
  return by_tick;
}

class InprocVsLockstep : public ::testing::TestWithParam<std::string> {};

// The in-process wiring and the LCM processes compute the same trajectory,
// bit for bit, for every shipped config.
TEST_P(InprocVsLockstep, TrajectoriesAreBitIdentical) {
  const std::string config = kConfigs + "/" + GetParam() + ".yaml";
  const std::string lockstep = freshDir("lockstep"), inproc = freshDir("inproc");
  const RunResult a = runScenario(config, lockstep, "-q --mode lockstep");
  const RunResult b = runScenario(config, inproc, "-q --mode inproc");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto ta = readTruth(lockstep + "/run.lcm"), tb = readTruth(inproc + "/run.lcm");
  const size_t common = forCommonTicks(ta, tb, [](const TruthSample& x, const TruthSample& y) {
    ASSERT_EQ(x.q, y.q) << "tick " << x.tick;
    ASSERT_EQ(x.qdot, y.qdot) << "tick " << x.tick;
    ASSERT_EQ(x.energy, y.energy) << "tick " << x.tick;
  });
  EXPECT_GE(common + 1, tb.size());  // inproc records every tick; lockstep may rarely miss one (see #7)
  const auto ca = readCommands(lockstep + "/run.lcm"), cb = readCommands(inproc + "/run.lcm");
  size_t same = 0;
  for (const auto& [tick, u] : ca)
    if (const auto it = cb.find(tick); it != cb.end()) {
      ASSERT_EQ(u, it->second) << "command of tick " << tick;
      ++same;
    }
  EXPECT_GE(same + 1, cb.size());
  EXPECT_EQ(readSummary(lockstep)["tracking"], readSummary(inproc)["tracking"]);
}

INSTANTIATE_TEST_SUITE_P(Configs, InprocVsLockstep, ::testing::ValuesIn(shippedConfigs()));

// The log misses nothing when the machine is busy: the logger lags, the
// plant waits for it (lockstep.logger_window) instead of overrunning its
// socket buffer. Two busy threads compete with the run's four processes.
TEST(Load, LockstepLogIsCompleteUnderCpuLoad) {
  std::atomic<bool> stop{false};
  std::vector<std::thread> hogs;
  for (int i = 0; i < 2; ++i)
    hogs.emplace_back([&stop] {
      volatile double x = 0.0;
      while (!stop) x = x + 1.0;
    });
  const std::string dir = freshDir("load");
  const RunResult r = runScenario(kConfigs + "/rigid_2dof.yaml", dir, "-q --set duration=5");
  stop = true;
  for (auto& h : hogs) h.join();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto truth = readTruth(dir + "/run.lcm");
  ASSERT_EQ(truth.size(), 5001u);
  for (size_t i = 0; i < truth.size(); ++i) ASSERT_EQ(truth[i].tick, static_cast<long long>(i));
  const auto j = readSummary(dir);
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["processes"]["logger"]["channels"]["PLANT_TRUTH"]["received"],
            j["processes"]["plant"]["channels"]["PLANT_TRUTH"]["published"]);
}

// The continuous-time closed loop of eqs. (600), (610a), (624) for m = 1:
// state [q, q', qc0, xi_1, qc_1, zeta_1] integrated by RK4 (step 0.1 ms);
// q at every tick of the scenario.
std::vector<Eigen::VectorXd> continuousChainM1(const config::Scenario& s) {
  const model::PlanarChain chain(s.robot);
  const model::Reference reference(s.reference);
  const controller::CascadedGains g{s.controller.gains, s.controller.stages};
  const controller::Theorem1Controller law(chain, reference, g.stage0, std::nullopt);
  const int n = s.dof();
  auto theta0Of = [&](double t, const Eigen::VectorXd& x) {
    return Eigen::VectorXd(x.segment(2 * n, n) +
                           g.stage0.b.cwiseProduct(x.head(n) - reference.evaluate(t, 0).q()));
  };
  auto cascade = [&](double t, const Eigen::VectorXd& x) {
    const controller::CascadeState st{x.segment(4 * n, n).transpose(), x.segment(5 * n, n).transpose()};
    const Eigen::VectorXd xi1_star = law.law(reference.evaluate(t, 2), x.head(n), theta0Of(t, x));
    return controller::evaluateCascade(g, xi1_star, x.segment(3 * n, n).transpose(), st);
  };
  auto field = [&](double t, const Eigen::VectorXd& x) {
    const controller::CascadeSignals sig = cascade(t, x);
    const controller::CascadeState d = controller::cascadeDerivative(g, sig);
    Eigen::VectorXd dx(6 * n);
    dx << x.segment(n, n), chain.acceleration(x.head(n), x.segment(n, n), x.segment(3 * n, n)),
        -g.stage0.a.cwiseProduct(theta0Of(t, x)), sig.u, d.qc.row(0).transpose(), d.zeta.row(0).transpose();
    return dx;
  };
  Eigen::VectorXd x(6 * n);
  const Eigen::VectorXd qt0 = s.initial_state.q - reference.evaluate(0.0, 0).q();
  x << s.initial_state.q, s.initial_state.qdot,
      s.controller.initial_filter_state.value_or(-g.stage0.b.cwiseProduct(qt0)),
      s.actuator.initial_state.row(0).transpose(), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n);
  std::vector<Eigen::VectorXd> q;
  const int per_tick = static_cast<int>(std::lround(s.tickPeriod() / 1e-4));
  const double h = s.tickPeriod() / per_tick;
  for (long long k = 0; k <= s.lastTick(); ++k) {
    const double t = k * s.tickPeriod();
    q.push_back(x.head(n));
    if (k == s.lastTick()) break;
    for (int i = 0; i < per_tick; ++i) x = rk4Step(field, t + i * h, x, h);
  }
  return q;
}

// The m = 1 lockstep run against the continuous closed loop: convergence
// times agree within 5 %.
TEST(ChainM1, MatchesTheContinuousTimeClosedLoop) {
  const std::string dir = freshDir("chain1");
  const RunResult r = runScenario(kConfigs + "/chain_m1.yaml", dir, "-q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const config::Scenario s = config::loadScenario(dir + "/config.resolved.yaml");
  ASSERT_EQ(s.actuator.order, 1);
  const std::vector<Eigen::VectorXd> x = continuousChainM1(s);
  const model::Reference reference(s.reference);
  logger::TrackingMetrics metrics(reference, s.metrics.tolerance);
  const auto truth = readTruth(dir + "/run.lcm");
  double worst = 0.0;
  for (long long k = 0; k <= s.lastTick(); ++k) metrics.addSample(k, k * s.tickPeriod(), x[k]);
  for (const TruthSample& sample : truth)
    worst = std::max(worst, (sample.q - x[sample.tick]).cwiseAbs().maxCoeff());
  const auto continuous = metrics.summary().convergence_time;
  ASSERT_TRUE(continuous.has_value());
  const double lockstep = readSummary(dir)["tracking"]["convergence_time"];
  std::printf("chain m = 1: convergence lockstep %.4f s, continuous %.4f s; max |dq| %.3e rad\n", lockstep,
              *continuous, worst);
  EXPECT_NEAR(lockstep, *continuous, 0.05 * *continuous);
  // The transients differ by up to ~0.1 rad (a 1 kHz controller, and xi_1 held
  // over each period, against a continuous one); after convergence both track.
  EXPECT_LT((truth.back().q - x.back()).norm(), s.metrics.tolerance);
}

// actuator.rate: the torque the plant sees converges to the chain's
// continuous xi_1(t) as the actuator updates more often. With 40 updates a
// period (one per physics step of chain_m1.yaml) as the reference, 10 updates
// come much closer to it than one (the hold error is O(1 / rate)).
TEST(ChainM1, AFasterActuatorConvergesToTheContinuousTorque) {
  auto trajectory = [](const std::string& rate) {
    const std::string dir = freshDir("actrate" + rate);
    const RunResult run =
        runScenario(kConfigs + "/chain_m1.yaml", dir, "-q --mode inproc --set actuator.rate=" + rate);
    EXPECT_EQ(run.exit_code, 0) << run.output;
    return readTruth(dir + "/run.lcm");
  };
  const auto reference = trajectory("40000"), once = trajectory("1000"), tenfold = trajectory("10000");
  ASSERT_EQ(once.size(), reference.size());
  ASSERT_EQ(tenfold.size(), reference.size());
  double gap_once = 0.0, gap_tenfold = 0.0;
  for (size_t k = 0; k < reference.size(); ++k) {
    gap_once = std::max(gap_once, (once[k].q - reference[k].q).cwiseAbs().maxCoeff());
    gap_tenfold = std::max(gap_tenfold, (tenfold[k].q - reference[k].q).cwiseAbs().maxCoeff());
  }
  std::printf("max |q - q(40 kHz actuator)|: actuator at 1 kHz %.3e rad, at 10 kHz %.3e rad\n", gap_once,
              gap_tenfold);
  EXPECT_GT(gap_once, 0.0);
  EXPECT_LT(gap_tenfold, 0.3 * gap_once);
}

// motor_rate: filtered -- the estimate's pole decides. At 1 kHz, a = 300 1/s
// tracks as well as the rate sensor; a = 1000 does not converge.
TEST(Flexible, FilteredMotorRateConvergesWithItsPoleAndNotWithAFastOne) {
  const std::string measured = freshDir("flexmeas"), slow = freshDir("flexslow"), fast = freshDir("flexfast");
  ASSERT_EQ(runScenario(kConfigs + "/flexible_2dof.yaml", measured, "-q --mode inproc").exit_code, 0);
  ASSERT_EQ(runScenario(kConfigs + "/flexible_2dof_filtered_rate.yaml", slow, "-q --mode inproc").exit_code,
            0);
  // Does not converge. With no artificial limit on the state the plant keeps
  // simulating (the motors spin fast but within what ODE can integrate), so
  // the run completes, misses its metric, and --check says so (exit 3).
  const RunResult r_fast = runScenario(kConfigs + "/flexible_2dof_filtered_rate.yaml", fast,
                                       "-q --mode inproc --check --set controller.motor_rate_pole=1000");
  EXPECT_EQ(r_fast.exit_code, 3) << r_fast.output;
  EXPECT_NE(r_fast.output.find("metric MISSED"), std::string::npos) << r_fast.output;
  const double e_measured = readSummary(measured)["tracking"]["final_error"];
  const double e_slow = readSummary(slow)["tracking"]["final_error"];
  const auto j_fast = readSummary(fast);
  std::printf("final ||q~||: measured rate %.3e, filtered a = 300 %.3e, a = 1000 %.3e rad\n", e_measured,
              e_slow, j_fast["tracking"]["final_error"].get<double>());
  EXPECT_LT(e_slow, 2.0 * e_measured + 1e-6);
  EXPECT_FALSE(j_fast["tracking"]["met"].get<bool>());
  EXPECT_GT(j_fast["tracking"]["samples"].get<long long>(), 1000);
  EXPECT_GT(j_fast["tracking"]["final_error"].get<double>(), 100.0 * e_slow);
}

// Assumption 2 in action: with a free-motion reference the m = 1 chain
// converges exactly (the error keeps shrinking); with a sinusoid it settles at
// a small residual, because xi_1* does not vanish on the reference.
TEST(ChainM1, FreeMotionReferenceConvergesExactlyWhereASinusoidLeavesAResidual) {
  const std::string free_dir = freshDir("free"), sine_dir = freshDir("sine");
  ASSERT_EQ(runScenario(kConfigs + "/chain_m1_free_motion.yaml", free_dir, "-q --mode inproc").exit_code, 0);
  ASSERT_EQ(runScenario(kConfigs + "/chain_m1.yaml", sine_dir, "-q --mode inproc").exit_code, 0);
  const double free_error = readSummary(free_dir)["tracking"]["final_error"];
  const double sine_error = readSummary(sine_dir)["tracking"]["final_error"];
  std::printf("final error: free motion %.3e rad, sinusoid %.3e rad\n", free_error, sine_error);
  EXPECT_LT(free_error, sine_error / 100.0);
}

TEST(LargeError, AnglesStayMultiTurnAndConverge) {
  const std::string dir = freshDir("large");
  const RunResult r = runScenario(kConfigs + "/rigid_2dof_large_error.yaml", dir, "-q --set duration=4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto truth = readTruth(dir + "/run.lcm");
  EXPECT_DOUBLE_EQ(truth.front().q(0), 100.0);  // started 16 turns out, not wrapped to (-pi, pi]
  for (size_t i = 1; i < truth.size(); ++i) {
    // Continuity: the change per tick matches the mean rate over it. The
    // transient reaches accelerations of 1e5 rad/s^2, so the trapezoid is
    // rough; a wrapped angle would be off by 2 pi.
    const Eigen::VectorXd predicted = 0.5 * 1e-3 * (truth[i].qdot + truth[i - 1].qdot);
    ASSERT_LT(((truth[i].q - truth[i - 1].q) - predicted).cwiseAbs().maxCoeff(), 2.0) << "tick " << i;
  }
  EXPECT_LT(readSummary(dir)["tracking"]["final_error"].get<double>(), 1e-3);
}

TEST(BadInput, ConfigErrorsStopBeforeAnyProcessStarts) {
  struct Case {
    std::string args, fragment;
  };
  const std::vector<Case> cases = {
      {"--set controller.kd=[-1,2]", "controller.kd: entry 1: expected a positive number"},
      {"--set controller.gain=3", "controller.gain: unknown key"},
      {"--set initial_state.q=[1,2,3]", "initial_state.q: expected a list of 2 numbers"},
      {"--set duration=abc", "duration: expected a finite number, got 'abc'"},
  };
  for (const Case& c : cases) {
    const std::string dir = freshDir("bad");
    const RunResult r = runScenario(kConfigs + "/rigid_2dof.yaml", dir, c.args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(c.fragment), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(fs::path(dir) / "run.lcm")) << "a process started for " << c.args;
  }
  const RunResult unwritable = runScenario(kConfigs + "/rigid_2dof.yaml", "/proc/lagrange-cannot-write");
  EXPECT_EQ(unwritable.exit_code, 2);
  EXPECT_NE(unwritable.output.find("cannot be created or written"), std::string::npos) << unwritable.output;
}

TEST(BadInput, ViolatedGainConditionWarnsOrRefusesUnderStrict) {
  const std::string config = kConfigs + "/rigid_2dof.yaml";
  const RunResult check = lagrange("check-gains " + quote(config) + " --set controller.kd=0.01");
  EXPECT_EQ(check.exit_code, 1);
  EXPECT_NE(check.output.find("VIOLATED"), std::string::npos) << check.output;
  const std::string dir = freshDir("strict");
  const RunResult strict = runScenario(config, dir, "--strict --set controller.kd=0.01");
  EXPECT_EQ(strict.exit_code, 2) << strict.output;
  EXPECT_FALSE(fs::exists(fs::path(dir) / "run.lcm"));
}

// Runs the default scenario for a long time and, once its log holds 100 kB,
// sends `sig` to the process whose argv[0] ends with `process`.
// A dead process: the launcher names it and its signal, stops the rest and
// keeps the log.
TEST(Failure, KilledControllerIsNamedAndTheLogIsKept) {
  const std::string dir = freshDir("kill");
  const SignalledRun run = signalMidRun(dir, kConfigs + "/rigid_2dof.yaml", "lagrange-controller", SIGKILL);
  ASSERT_TRUE(run.signalled);
  EXPECT_EQ(run.result.exit_code, 1) << run.result.output;
  EXPECT_NE(run.result.output.find("process 'controller' was killed by signal 9"), std::string::npos)
      << run.result.output;
  EXPECT_GT(readTruth(dir + "/run.lcm").size(), 10u);  // the log is readable
}

// Ctrl-C: every process stops cleanly, the log and the summary are kept.
TEST(Failure, InterruptStopsEveryProcessAndKeepsTheOutputs) {
  const std::string dir = freshDir("interrupt");
  const SignalledRun run = signalMidRun(dir, kConfigs + "/rigid_2dof.yaml", "bin/lagrange", SIGINT);
  const RunResult& r = run.result;
  const bool interrupted = run.signalled;
  ASSERT_TRUE(interrupted);
  EXPECT_EQ(r.exit_code, 130) << r.output;
  const auto j = readSummary(dir);
  EXPECT_EQ(j["status"], "interrupted");
  for (const char* p : {"plant", "controller", "actuator"})
    EXPECT_EQ(j["processes"][p]["state"], "interrupted") << p;
  EXPECT_EQ(findProcess("lagrange-plant", dir), -1) << "a process outlived the launcher";
  const auto truth = readTruth(dir + "/run.lcm");
  EXPECT_GT(truth.size(), 10u);
  EXPECT_EQ(j["tracking"]["samples"].get<size_t>(), truth.size());  // nothing recorded was lost
}

// Realtime: the same scenario on fixed-rate loops converges like lockstep,
// and reports its timing. (Timing numbers are benchmarks, not asserted.)
TEST_F(DefaultRun, RealtimeConvergesLikeLockstepAndReportsTiming) {
  ASSERT_EQ(result_.exit_code, 0) << result_.output;
  const std::string dir = freshDir("realtime");
  const RunResult r = runScenario(kConfigs + "/rigid_2dof.yaml", dir, "-q --mode realtime");
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
    EXPECT_GT(loop["cycles"].get<long long>(), 9000) << p;
    for (const char* key : {"achieved_rate", "deadline_misses", "longest_miss_run", "on_time_fraction"})
      EXPECT_TRUE(loop.contains(key)) << p << " " << key;
    EXPECT_LE(loop["jitter"]["p50"].get<double>(), loop["jitter"]["max"].get<double>());
  }
  EXPECT_GT(j["timing"]["latency"]["p50"].get<double>(), 0.0);
  EXPECT_TRUE(j["messages"]["stale"]["plant"].contains("torque_zeroed"));
}

// Stale inputs: a controller frozen for 300 ms (SIGSTOP) sends nothing; the
// plant's policy zeroes (or holds) the torque and counts it, the controller
// refuses the positions that aged while it was frozen, and the arm converges
// again afterwards.
class StaleTorquePolicy : public ::testing::TestWithParam<std::string> {};

TEST_P(StaleTorquePolicy, TriggersWhenTheControllerStopsAndTheArmRecovers) {
  const std::string dir = freshDir("stale");
  std::atomic<bool> done{false};
  RunResult r;
  // Under `zero` every scheduling hiccup longer than max_torque_age (default
  // 2 ms) drops the arm for a period; on a loaded machine those kicks kept it
  // from settling after the freeze (final error 1e-3..2e-2 in some runs).
  // Fresh for 20 ms, a torque rides out hiccups while the 300 ms freeze still
  // zeroes at least 280 periods.
  const std::string age = GetParam() == "zero" ? " --set realtime.max_torque_age=20" : "";
  std::thread runner([&] {
    r = runScenario(kConfigs + "/rigid_2dof.yaml", dir,
                    "-q --mode realtime --set duration=5 --set realtime.stale_torque=" + GetParam() +
                        " --set realtime.hold_periods=100" + age);
    done = true;
  });
  bool frozen = false;
  for (int i = 0; i < 200 && !frozen && !done; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!fs::exists(fs::path(dir) / "run.lcm") || fs::file_size(fs::path(dir) / "run.lcm") < 600000) continue;
    const pid_t pid = findProcess("lagrange-controller", dir);
    if (pid > 0 && kill(pid, SIGSTOP) == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      kill(pid, SIGCONT);
      frozen = true;
    }
  }
  runner.join();
  ASSERT_TRUE(frozen);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(dir);
  const auto& plant = j["messages"]["stale"]["plant"];
  const long long zeroed = plant["torque_zeroed"], held = plant["torque_held"];
  const long long stale_positions = j["messages"]["stale"]["controller"]["stale_inputs"];
  std::printf("policy %s: torque held %lld periods, zeroed %lld; controller refused %lld stale positions\n",
              GetParam().c_str(), held, zeroed, stale_positions);
  if (GetParam() == "hold") {
    EXPECT_GE(held, 90);     // held for hold_periods = 100 ...
    EXPECT_GE(zeroed, 100);  // ... then zeroed for the rest of the freeze
  } else {
    EXPECT_EQ(held, 0);
    EXPECT_GE(zeroed, 200);
  }
  // stale_positions is printed, not asserted: whether the resumed controller
  // finds its newest position already too old depends on where in the period
  // it wakes (0 in some runs, 3-19 in others).
  EXPECT_GT(j["tracking"]["max_error"].get<double>(), 1e-2);    // the freeze really disturbed the arm
  EXPECT_LT(j["tracking"]["final_error"].get<double>(), 1e-3);  // and it converged again
}

INSTANTIATE_TEST_SUITE_P(Policies, StaleTorquePolicy, ::testing::Values("zero", "hold"));

// Malformed messages are rejected, counted, and the run still converges.
template <class Msg>
std::vector<uint8_t> encoded(const Msg& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// The run identity the bad-traffic runs use, so that injected messages pass
// the run check and reach the checks under test.
constexpr int64_t kTestRunId = 4242;

// A message as a given publisher would send it: this run, a fresh sequence number.
template <class Msg>
std::vector<uint8_t> fromPublisher(Msg m, const std::string& publisher, int64_t seq,
                                   int64_t run_id = kTestRunId) {
  m.header.run_id = run_id;
  m.header.publisher = publisher;
  m.header.publisher_pid = 1;
  m.header.seq = seq;
  transport::seal(m);
  return encoded(m);
}

// Runs a scenario on the machine's network (inside the test's namespace) at
// `url` with run id kTestRunId while publishing, every 5 ms for the whole run,
// the payloads `make(n)` returns for the n-th round on `channel`.
// Returns the run's result and how many bad messages were sent.
std::pair<RunResult, int> runUnderBadTraffic(
    const std::string& config, const std::string& dir, const std::string& url, const std::string& channel,
    const std::function<std::vector<std::vector<uint8_t>>(int64_t)>& make, const std::string& extra = "") {
  std::atomic<bool> done{false};
  RunResult r;
  std::thread runner([&] {
    r = runScenario(
        config, dir,
        "--no-netns -q --run-id " + std::to_string(kTestRunId) + " --lcm-url '" + url + "' " + extra);
    done = true;
  });
  lcm_t* lcm = lcm_create(url.c_str());
  int sent = 0;
  for (int64_t round = 1; !done && lcm; ++round) {
    for (const auto& p : make(round))
      lcm_publish(lcm, channel.c_str(), p.data(), static_cast<unsigned>(p.size()));
    sent += static_cast<int>(make(round).size());
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  runner.join();
  if (lcm) lcm_destroy(lcm);
  return {r, sent};
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  return {(std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()};
}

// Malformed messages are rejected, counted, and the run still converges; the
// run must neither crash nor stall (a logger that drained "until quiet" once
// never finished).
TEST(Failure, MalformedPositionMessagesAreRejectedAndCounted) {
  const std::string dir = freshDir("garbage");
  lagrange::plant_position_t wrong_size;  // decodes, but 3 joints on a 2-joint robot
  wrong_size.header = transport::makeHeader(5, 0.005);
  wrong_size.num_joints = 3;
  wrong_size.q = {1, 2, 3};
  lagrange::plant_position_t nan_msg = wrong_size;
  nan_msg.num_joints = 2;
  nan_msg.q = {std::nan(""), 0.0};
  const std::vector<uint8_t> garbage = {0xde, 0xad, 0xbe, 0xef, 1, 2, 3};
  const auto [r, sent] = runUnderBadTraffic(
      kConfigs + "/rigid_2dof.yaml", dir, "udpm://239.255.76.67:7671?ttl=0", "PLANT_POSITION",
      [&](int64_t n) {
        return std::vector<std::vector<uint8_t>>{garbage, fromPublisher(wrong_size, "plant", 2 * n),
                                                 fromPublisher(nan_msg, "plant", 2 * n + 1)};
      });
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(dir);
  const long long rejected = j["processes"]["controller"]["channels"]["PLANT_POSITION"]["rejected"];
  std::printf("sent %d bad messages; the controller rejected %lld\n", sent, rejected);
  EXPECT_GE(rejected, 3);                         // the fault happened ...
  EXPECT_TRUE(j["tracking"]["met"].get<bool>());  // ... and the run coped
  EXPECT_LT(j["timing"]["wall_time"].get<double>(), 30.0) << "the run stalled under bad traffic";
  const std::string text = readText(dir + "/controller.log");
  EXPECT_NE(text.find("undecodable"), std::string::npos);
  EXPECT_NE(text.find("num_joints is 3, expected 2"), std::string::npos);
  EXPECT_NE(text.find("non-finite"), std::string::npos);
  const auto& reasons = j["processes"]["controller"]["channels"]["PLANT_POSITION"]["rejected_by_reason"];
  EXPECT_GE(reasons["undecodable"].get<long long>(), 1) << reasons.dump();
  EXPECT_GE(reasons["invalid"].get<long long>(), 2) << reasons.dump();
}

// Message hygiene: well-formed positions of another run, of a process that is
// not the plant, and repeats of one sequence number are rejected per reason
// before any validation, and the run converges. (Their tick would pin a
// realtime controller, and answering them would stall a lockstep one.)
TEST(Failure, MessagesOfAnotherRunAnotherPublisherOrRepeatedAreRejected) {
  const std::string dir = freshDir("hygiene");
  lagrange::plant_position_t position;
  position.header = transport::makeHeader(1000000000, 1e6);
  position.num_joints = 2;
  position.q = {0.1, 0.2};
  lagrange::plant_position_t repeated = position;
  repeated.header = transport::makeHeader(0, 0.0);  // an old tick: harmless even the once it is new
  const auto [r, sent] =
      runUnderBadTraffic(kConfigs + "/rigid_2dof.yaml", dir, "udpm://239.255.76.67:7673?ttl=0",
                         "PLANT_POSITION", [&](int64_t n) {
                           return std::vector<std::vector<uint8_t>>{
                               fromPublisher(position, "plant", n, kTestRunId + 1),
                               fromPublisher(position, "intruder", n), fromPublisher(repeated, "plant", 7)};
                         });
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(dir);
  EXPECT_EQ(j["run_id"], kTestRunId);
  const auto& reasons = j["processes"]["controller"]["channels"]["PLANT_POSITION"]["rejected_by_reason"];
  std::printf("sent %d foreign messages; the controller rejected %s\n", sent, reasons.dump().c_str());
  EXPECT_GE(reasons["other_run"].get<long long>(), 3) << reasons.dump();
  EXPECT_GE(reasons["wrong_publisher"].get<long long>(), 3) << reasons.dump();
  EXPECT_GE(reasons["old_or_repeated"].get<long long>(), 2) << reasons.dump();  // every copy but the first
  EXPECT_EQ(reasons["invalid"], 0);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  const std::string text = readText(dir + "/controller.log");
  EXPECT_NE(text.find("from another run (run_id 4243, this run is 4242"), std::string::npos) << text;
  EXPECT_NE(text.find("published by 'intruder', expected 'plant'"), std::string::npos) << text;
  EXPECT_NE(text.find("sequence number 7 of 'plant' not newer than 7"), std::string::npos) << text;
}

// An ACTUATOR_STATE of the wrong chain order or size reaching the cascaded
// controller is rejected with the reason, one with the wrong number of torque
// steps is rejected by the plant, and the m = 1 run converges.
TEST(Failure, WrongActuatorStatesAreRejectedByTheCascadedController) {
  const std::string dir = freshDir("badchain");
  lagrange::actuator_state_t wrong_order;  // tick far in the future: the plant ignores it
  wrong_order.header = transport::makeHeader(1000000000, 1e6);
  wrong_order.input_command_tick = wrong_order.header.tick;
  wrong_order.num_joints = 2;
  wrong_order.order = 2;
  wrong_order.u_commanded = {0.0, 0.0};
  wrong_order.torque_steps = 1;
  wrong_order.tau_applied = {{0.0, 0.0}};
  wrong_order.saturated = {0, 0};
  wrong_order.xi = {{1.0, 1.0}, {1.0, 1.0}};
  lagrange::actuator_state_t wrong_size = wrong_order;
  wrong_size.order = 1;
  wrong_size.num_joints = 3;
  wrong_size.u_commanded = {0.0, 0.0, 0.0};
  wrong_size.tau_applied = {{0.0, 0.0, 0.0}};
  wrong_size.saturated = {0, 0, 0};
  wrong_size.xi = {{1.0, 1.0, 1.0}};
  lagrange::actuator_state_t wrong_steps = wrong_order;  // chain_m1.yaml updates once a period
  wrong_steps.order = 1;
  wrong_steps.xi = {{1.0, 1.0}};
  wrong_steps.torque_steps = 2;
  wrong_steps.tau_applied = {{0.0, 0.0}, {0.0, 0.0}};
  const auto [r, sent] = runUnderBadTraffic(
      kConfigs + "/chain_m1.yaml", dir, "udpm://239.255.76.67:7672?ttl=0", "ACTUATOR_STATE", [&](int64_t n) {
        return std::vector<std::vector<uint8_t>>{fromPublisher(wrong_order, "actuator", 3 * n),
                                                 fromPublisher(wrong_size, "actuator", 3 * n + 1),
                                                 fromPublisher(wrong_steps, "actuator", 3 * n + 2)};
      });
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = readSummary(dir);
  const long long rejected = j["processes"]["controller"]["channels"]["ACTUATOR_STATE"]["rejected"];
  std::printf("sent %d bad actuator states; the controller rejected %lld\n", sent, rejected);
  EXPECT_GE(rejected, 2);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>());
  const std::string text = readText(dir + "/controller.log");
  EXPECT_NE(text.find("actuator order is 2, expected 1"), std::string::npos);
  EXPECT_NE(text.find("num_joints is 3, expected 2"), std::string::npos);
  EXPECT_GE(j["processes"]["plant"]["channels"]["ACTUATOR_STATE"]["rejected"].get<long long>(), 2);
  EXPECT_NE(readText(dir + "/plant.log").find("torque_steps is 2, expected 1"), std::string::npos);
}

}  // namespace
}  // namespace lagrange::testing
