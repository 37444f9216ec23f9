// The golden logs (tests/data/golden, recorded by scripts/record_golden.sh):
// every component replays its recorded outputs bit for bit -- lockstep and
// realtime, rigid, actuator chain and flexible joints -- and the replay test
// has teeth: a perturbed gain or a changed discretisation fails it at the
// first tick the change can show. A failure here after an intended change of
// the outputs means: re-record with `bash scripts/record_golden.sh`.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <regex>

#include "support/configs.hpp"
#include "support/launch.hpp"

namespace lagrange::testing {
namespace {

const char* kRerecord = "\n(if this change of the outputs is intended: bash scripts/record_golden.sh)";

std::string golden(const std::string& name) { return kGoldenDir + name + ".lcm"; }

const std::vector<std::string> kLogs = {"rigid_2dof_lockstep", "chain_m2_lockstep",
                                        "flexible_2dof_filtered_rate_lockstep", "chain_m1_realtime",
                                        "panda_theorem1_lockstep"};  // a URDF arm, its URDF text in SCENARIO

// How many outputs `lagrange replay` says it reproduced, or -1.
long long reproduced(const RunResult& r) {
  std::smatch m;
  if (!std::regex_search(r.output, m, std::regex("reproduced all ([0-9]+) recorded outputs"))) return -1;
  return std::stoll(m[1]);
}

TEST(Golden, EveryComponentReplaysEveryGoldenLogExactly) {
  for (const auto& name : kLogs)
    for (const std::string component : {"controller", "actuator", "plant"}) {
      const RunResult r = lagrange("replay " + quote(golden(name)) + " --component " + component);
      EXPECT_EQ(r.exit_code, 0) << name << " " << component << ": " << r.output << kRerecord;
      // One output per tick of the 1 s recordings (the realtime actuator may
      // have missed answering the last sample before the plant stopped).
      EXPECT_GE(reproduced(r), 1000) << name << " " << component << ": " << r.output;
      EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    }
}

// The logs are plain LCM logs: lcm::LogFile reads them, SCENARIO first.
TEST(Golden, LogsAreStandardLcmLogsThatStartWithTheScenario) {
  for (const auto& name : kLogs) {
    lcm::LogFile log(golden(name), "r");
    ASSERT_TRUE(log.good()) << name;
    const lcm::LogEvent* first = log.readNextEvent();
    ASSERT_NE(first, nullptr) << name;
    EXPECT_EQ(first->channel, "SCENARIO") << name;
    long long events = 1;
    while (log.readNextEvent()) ++events;
    EXPECT_GT(events, 4000) << name;  // 4 messages per tick at least, 1001 ticks
  }
}

struct Perturbation {
  std::string log, component, override_, where;
};

// Each change must be caught at the first tick it can change an output:
// kp enters u at once; the filter pole a first matters at tick 2 (bumpless
// start: qc(1) = -b q~(0) whatever a is); the actuator's update rate changes
// the torque profile of tick 0; the physics step the state at tick 1; the
// joint stiffness the spring energy of tick 0.
TEST(Golden, APerturbedGainOrDiscretisationFailsAtTheRightTick) {
  const std::vector<Perturbation> cases = {
      {"rigid_2dof_lockstep", "controller", "controller.kp=[150.001,10]",
       "at tick 0 (t = 0.000000 s): CONTROL_COMMAND.u[1]: recorded"},
      {"chain_m2_lockstep", "controller", "controller.a=[50.001,50]",
       "at tick 2 (t = 0.002000 s): CONTROL_COMMAND."},
      {"chain_m1_realtime", "controller", "controller.kp=[150,10.001]",
       "at tick 0 (t = 0.000000 s): CONTROL_COMMAND.u[2]"},
      {"chain_m2_lockstep", "actuator", "actuator.rate=2000",
       "at tick 0 (t = 0.000000 s): ACTUATOR_STATE.tau_applied: recorded 1 steps, replayed 2"},
      {"chain_m1_realtime", "plant", "plant.physics_step=5e-5",
       "at tick 1 (t = 0.001000 s): PLANT_TRUTH.q[1]"},
      {"flexible_2dof_filtered_rate_lockstep", "plant", "robot.flexible.stiffness=[100,30.001]",
       "at tick 0 (t = 0.000000 s): PLANT_TRUTH.potential_energy"},
  };
  for (const auto& c : cases) {
    const RunResult r = lagrange("replay " + quote(golden(c.log)) + " --component " + c.component +
                                 " --set " + quote(c.override_));
    EXPECT_EQ(r.exit_code, 1) << c.log << " " << c.override_ << ": " << r.output;
    EXPECT_NE(r.output.find("DIVERGED"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.where), std::string::npos) << c.override_ << ": " << r.output;
  }
}

}  // namespace
}  // namespace lagrange::testing
