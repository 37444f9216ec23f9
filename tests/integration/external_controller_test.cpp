// A controller from outside the project (controller.type external): the Java
// PD of examples/external_controller/, compiled here with javac and never by
// CMake, takes the controller's place over the LCM contract of
// docs/external_controllers.md -- in lockstep and in realtime -- and its runs
// replay: `lagrange replay --component controller` runs it again on the
// recorded positions and gets every recorded command back bit for bit.
#include <gtest/gtest.h>

#include <fstream>

#include "support/launch.hpp"
#include "support/run_log.hpp"

namespace lagrange::testing {
namespace {

const std::string kClassPath =
    std::string("/usr/share/java/lcm.jar:") + LAGRANGE_BIN_DIR + "/../share/java/lagrange_lcmtypes.jar";

// The PD's class directory, compiled once for the tests here.
const std::string& pdClasses() {
  static const std::string dir = [] {
    const std::string out = freshDir("external-pd-classes");
    const RunResult r =
        shell("javac -cp " + kClassPath + " -d " + quote(out) + " " +
              quote(std::string(LAGRANGE_SOURCE_DIR) + "/examples/external_controller/PdController.java"));
    if (r.exit_code != 0) throw std::runtime_error("javac failed: " + r.output);
    return out;
  }();
  return dir;
}

// The Pelican without gravity, regulated by the external PD to a constant q_d.
const Eigen::Vector2d kKp(20.0, 5.0), kKd(4.0, 1.0), kQd(0.5, -0.2);
std::string scenario(const std::string& mode) {
  const std::string path = freshDir("external-config") + ".yaml";
  std::ofstream(path)
      << "name: external_pd\nduration: 3.0\nmode: " << mode
      << "\nrobot: {preset: pelican, gravity: 0.0}\n"
         "initial_state: {q: [0.2, -0.1], qdot: [0.0, 0.0]}\n"
         "reference: {type: sine, offset: [0.5, -0.2], amplitude: [0.0, 0.0], frequency: [0.0, 0.0]}\n"
         "plant: {physics_step: 1.0e-4, publish_rate: 1000}\n"
         "controller:\n  type: external\n  command: [java, -cp, \""
      << pdClasses() << ":" << kClassPath
      << "\", PdController, --kp, \"20,5\", --kd, \"4,1\", --qd, \"0.5,-0.2\"]\n"
         "metrics: {tolerance: 1.0e-3, convergence_deadline: 2.0}\n";
  return path;
}

TEST(ExternalController, AJavaPdTakesTheControllersPlaceInLockstepAndItsRunReplays) {
  const std::string out = freshDir("external-lockstep");
  const RunResult run = runScenario(scenario("lockstep"), out, "");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("gain conditions NOT CHECKED: external controller (java)"), std::string::npos)
      << run.output;
  const auto j = readSummary(out);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  // Every command is the PD law on the positions it answered, as written here.
  const auto positions = readPositions(out + "/run.lcm");
  const auto commands = readCommands(out + "/run.lcm");
  ASSERT_EQ(commands.size(), 3001u);
  for (long long k = 1; k <= 3000; ++k) {
    for (int i = 0; i < 2; ++i) {
      const double q = positions.at(k)[i], v = (q - positions.at(k - 1)[i]) / 1e-3;
      EXPECT_NEAR(commands.at(k)[i], -kKp(i) * (q - kQd(i)) - kKd(i) * v, 1e-9) << "tick " << k;
    }
  }
  for (const std::string component : {"controller", "actuator", "plant"}) {
    const RunResult replay = lagrange("replay " + quote(out + "/run.lcm") + " --component " + component);
    EXPECT_EQ(replay.exit_code, 0) << component << ": " << replay.output;
    EXPECT_NE(replay.output.find("reproduced all 3001 recorded outputs"), std::string::npos) << replay.output;
  }
  // A changed gain is caught: the replayed controller is the program, with the log's scenario.
  const RunResult changed = lagrange(
      "replay " + quote(out + "/run.lcm") + " --set 'controller.command=[java, -cp, \"" + pdClasses() + ":" +
      kClassPath + "\", PdController, --kp, \"21,5\", --kd, \"4,1\", --qd, \"0.5,-0.2\"]'");
  EXPECT_EQ(changed.exit_code, 1) << changed.output;
  EXPECT_NE(changed.output.find("DIVERGED after 1 outputs at tick 0"), std::string::npos) << changed.output;
}

TEST(ExternalController, AJavaPdRunsInRealtimeAndItsRunReplays) {
  const std::string out = freshDir("external-realtime");
  const RunResult run = runScenario(scenario("realtime"), out, "-q");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // The program publishes no STATUS, so its commands cannot be counted
  // against a published total; convergence shows it answered, and how many
  // ticks it answered depends on the machine's load, so no count is asserted.
  EXPECT_TRUE(readSummary(out)["tracking"]["met"].get<bool>());
  const RunResult replay = lagrange("replay " + quote(out + "/run.lcm") + " --component controller");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("reproduced all"), std::string::npos) << replay.output;
}

}  // namespace
}  // namespace lagrange::testing
