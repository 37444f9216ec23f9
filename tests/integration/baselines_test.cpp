// The baselines (docs/baselines.md) as a user runs them: named in
// controller.type, known to every process of the stock programs, the same
// trajectory in lockstep and in-process bit for bit, and the report saying
// which claims come with them.
#include <gtest/gtest.h>

#include <fstream>

#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

// The Pelican tracking the default scenario's sinusoid, PD+ on differenced
// positions at 1 kHz, its gains those of configs/rigid_2dof.yaml's stage.
constexpr const char* kPdPlusDifferenced = R"(name: pd_plus_differenced_pelican
duration: 3.0
mode: lockstep
robot:
  preset: pelican
initial_state:
  q: [0.5, -0.5]
  qdot: [0.0, 0.0]
reference:
  type: sine
  offset: [0.1, 0.2]
  amplitude: [0.5, 0.3]
  frequency: [2.0, 3.0]
plant:
  physics_step: 1.0e-4
  publish_rate: 1000
controller:
  type: pd_plus_differenced
  kp: [150.0, 10.0]
  kd: [15.0, 1.0]
metrics:
  tolerance: 1.0e-3
  convergence_deadline: 2.0
)";

// The Pelican regulated to a constant q_d (a sine of amplitude 0) from 1.5 rad
// away by Kelly's set-point controller.
constexpr const char* kSetPoint = R"(name: set_point_pelican
duration: 3.0
mode: lockstep
robot:
  preset: pelican
initial_state:
  q: [-0.5, 1.0]
  qdot: [0.0, 0.0]
reference:
  type: sine
  offset: [0.5, -0.2]
  amplitude: [0.0, 0.0]
  frequency: [0.0, 0.0]
plant:
  physics_step: 1.0e-4
  publish_rate: 1000
controller:
  type: set_point
  kp: [100.0, 20.0]
  kd: [10.0, 2.0]
  a: [50.0, 50.0]
  b: [50.0, 50.0]
metrics:
  tolerance: 1.0e-3
  convergence_deadline: 2.0
)";

// Nicosia and Tomei's observer-based PD+ from 0.1 rad off the default
// sinusoid (the paper claims local tracking), observer poles at 50 1/s.
constexpr const char* kNicosiaTomei = R"(name: nicosia_tomei_pelican
duration: 3.0
mode: lockstep
robot:
  preset: pelican
initial_state:
  q: [0.2, 0.1]
  qdot: [0.0, 0.0]
reference:
  type: sine
  offset: [0.1, 0.2]
  amplitude: [0.5, 0.3]
  frequency: [2.0, 3.0]
plant:
  physics_step: 1.0e-4
  publish_rate: 1000
controller:
  type: nicosia_tomei
  kp: [150.0, 10.0]
  kd: [15.0, 1.0]
  lp: [2500.0, 2500.0]
  ld: [100.0, 100.0]
metrics:
  tolerance: 1.0e-3
  convergence_deadline: 2.0
)";

// Berghuis and Nijmeijer's controller-observer from 0.3 rad off the sinusoid.
constexpr const char* kBerghuisNijmeijer = R"(name: berghuis_nijmeijer_pelican
duration: 3.0
mode: lockstep
robot:
  preset: pelican
initial_state:
  q: [0.4, -0.1]
  qdot: [0.0, 0.0]
reference:
  type: sine
  offset: [0.1, 0.2]
  amplitude: [0.5, 0.3]
  frequency: [2.0, 3.0]
plant:
  physics_step: 1.0e-4
  publish_rate: 1000
controller:
  type: berghuis_nijmeijer
  kp: [150.0, 10.0]
  kd: [15.0, 1.0]
  lambda: [10.0, 10.0]
  lp: [2500.0, 2500.0]
  ld: [100.0, 100.0]
metrics:
  tolerance: 1.0e-3
  convergence_deadline: 2.0
)";

struct Baseline {
  const char* type;
  const char* config;
  const char* report;  // what the run prints about its gains
};

// Test names and messages show the type, not the struct's bytes.
void PrintTo(const Baseline& b, std::ostream* os) { *os << b.type; }

class Baselines : public ::testing::TestWithParam<Baseline> {};

TEST_P(Baselines, RunTheSameInLockstepAndInProcessMeetTheirMetricAndReplay) {
  const std::string config = freshDir(std::string("baseline-config-") + GetParam().type) + ".yaml";
  std::ofstream(config) << GetParam().config;
  const std::string lockstep = freshDir("baseline-lockstep"), inproc = freshDir("baseline-inproc");
  const RunResult a = runScenario(config, lockstep, "--mode lockstep");
  const RunResult b = runScenario(config, inproc, "-q --mode inproc");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  // What its paper claims, and that nothing more is checked.
  EXPECT_NE(a.output.find(GetParam().report), std::string::npos) << a.output;
  const auto ta = readTruth(lockstep + "/run.lcm"), tb = readTruth(inproc + "/run.lcm");
  ASSERT_EQ(ta.size(), 3001u);
  ASSERT_EQ(tb.size(), 3001u);
  for (size_t k = 0; k < ta.size(); ++k) ASSERT_EQ(ta[k].q, tb[k].q) << "tick " << k;
  EXPECT_EQ(readCommands(lockstep + "/run.lcm"), readCommands(inproc + "/run.lcm"));
  const auto j = readSummary(lockstep);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  EXPECT_EQ(j["controller"]["type"], GetParam().type) << j["controller"].dump();
  // Its log replays through the controller exactly.
  const RunResult replay = lagrange("replay " + quote(lockstep + "/run.lcm") + " --component controller");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("reproduced all 3001 recorded outputs"), std::string::npos) << replay.output;
}

INSTANTIATE_TEST_SUITE_P(
    Registered, Baselines,
    ::testing::Values(
        Baseline{"pd_plus_differenced", kPdPlusDifferenced,
                 "no stability condition is known for controller type 'pd_plus_differenced'"},
        Baseline{"set_point", kSetPoint, "Kelly (IFAC 1993) proves global asymptotic regulation"},
        Baseline{"nicosia_tomei", kNicosiaTomei, "Nicosia and Tomei (IEEE TAC 1990) prove local tracking"},
        Baseline{"berghuis_nijmeijer", kBerghuisNijmeijer,
                 "Berghuis and Nijmeijer (IEEE TRA 1993) prove semiglobal exponential tracking"}),
    [](const ::testing::TestParamInfo<Baseline>& param) { return std::string(param.param.type); });

}  // namespace
}  // namespace lagrange::testing
