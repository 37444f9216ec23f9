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

// The default sinusoid, and a constant q_d for the set-point controller.
constexpr const char* kSine =
    "{type: sine, offset: [0.1, 0.2], amplitude: [0.5, 0.3], frequency: [2.0, 3.0]}";
constexpr const char* kConstant =
    "{type: sine, offset: [0.5, -0.2], amplitude: [0.0, 0.0], frequency: [0.0, 0.0]}";

struct Baseline {
  const char* type;
  const char* initial_q;     // [rad]
  const char* reference;     // the reference section, flow style
  const char* gains;         // the controller's keys, flow style
  const char* report;        // what the run prints about its gains
  const char* sensors = "";  // a sensors section, flow style, for those that measure the velocity
};

// The Pelican for 3 s at 1 kHz, judged on ||q~|| below 1e-3 rad within 2 s.
std::string scenario(const Baseline& b) {
  return std::string("name: ") + b.type +
         "_pelican\nduration: 3.0\nmode: lockstep\nrobot: {preset: pelican}\n" +
         "initial_state: {q: " + b.initial_q + ", qdot: [0.0, 0.0]}\nreference: " + b.reference +
         "\nplant: {physics_step: 1.0e-4, publish_rate: 1000}\ncontroller: {type: " + b.type + ", " +
         b.gains + "}\nmetrics: {tolerance: 1.0e-3, convergence_deadline: 2.0}\n" +
         (*b.sensors ? std::string("sensors: ") + b.sensors + "\n" : "");
}

// Test names and messages show the type, not the struct's bytes.
void PrintTo(const Baseline& b, std::ostream* os) { *os << b.type; }

class Baselines : public ::testing::TestWithParam<Baseline> {};

TEST_P(Baselines, RunTheSameInLockstepAndInProcessMeetTheirMetricAndReplay) {
  const std::string config = freshDir(std::string("baseline-config-") + GetParam().type) + ".yaml";
  std::ofstream(config) << scenario(GetParam());
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

// PD+ and Slotine-Li on an exact velocity sensor, from 0.6 rad off; PD+ on
// differenced positions with configs/rigid_2dof.yaml's stage gains;
// Kelly's set-point controller from 1.5 rad away; the two observer designs
// from 0.1 rad (Nicosia-Tomei: local) and 0.3 rad (Berghuis-Nijmeijer:
// semiglobal) off, observer poles at 50 1/s.
INSTANTIATE_TEST_SUITE_P(
    Registered, Baselines,
    ::testing::Values(
        Baseline{"pd_plus", "[0.7, -0.4]", kSine, "kp: [150.0, 10.0], kd: [15.0, 1.0]",
                 "Paden and Panja (Int. J. Control 1988) prove global (asymptotic) tracking",
                 "{velocity: {}}"},
        Baseline{"slotine_li", "[0.7, -0.4]", kSine, "lambda: [10.0, 10.0], kd: [20.0, 2.0]",
                 "Slotine and Li (Int. J. Robotics Research 1987) prove global (asymptotic) tracking",
                 "{velocity: {}}"},
        Baseline{"pd_plus_differenced", "[0.5, -0.5]", kSine, "kp: [150.0, 10.0], kd: [15.0, 1.0]",
                 "no stability condition is known for controller type 'pd_plus_differenced'"},
        Baseline{"set_point", "[-0.5, 1.0]", kConstant,
                 "kp: [100.0, 20.0], kd: [10.0, 2.0], a: [50.0, 50.0], b: [50.0, 50.0]",
                 "Kelly (IFAC 1993) proves global asymptotic regulation"},
        Baseline{"nicosia_tomei", "[0.2, 0.1]", kSine,
                 "kp: [150.0, 10.0], kd: [15.0, 1.0], lp: [2500.0, 2500.0], ld: [100.0, 100.0]",
                 "Nicosia and Tomei (IEEE TAC 1990) prove local tracking"},
        Baseline{"berghuis_nijmeijer", "[0.4, -0.1]", kSine,
                 "kp: [150.0, 10.0], kd: [15.0, 1.0], lambda: [10.0, 10.0], lp: [2500.0, 2500.0], "
                 "ld: [100.0, 100.0]",
                 "Berghuis and Nijmeijer (IEEE TRA 1993) prove semiglobal exponential tracking"}),
    [](const ::testing::TestParamInfo<Baseline>& param) { return std::string(param.param.type); });

}  // namespace
}  // namespace lagrange::testing
