// Nothing waits forever (lockstep.stall_timeout, plant/stall_diagnosis.hpp):
// a controller that never answers, or whose every command fails the check,
// stops the run with exit 1 within the deadline, and the plant's last words
// name whom it waited for, on which channel, and what was seen instead.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/signal_run.hpp"

namespace lagrange::testing {
namespace {

const std::string kRigid = std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml";

struct Timed {
  RunResult result;
  double seconds;
};

Timed timedRun(const std::string& out, const std::string& extra) {
  const auto start = std::chrono::steady_clock::now();
  RunResult r = runScenario(kRigid, out, "--set lockstep.stall_timeout=2 " + extra);
  return {r, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A program in the controller's place that never says anything: the first
// tick goes unanswered. The start gets 3 x stall_timeout (2 s: room for a
// sanitizer build's slower start), then the plant stops.
TEST(Stall, AControllerThatNeverAnswersStopsTheRunNamingIt) {
  const std::string out = freshDir("stall-silent");
  const Timed t = timedRun(out, "--set 'controller={type: external, command: [sleep, \"600\"]}'");
  EXPECT_EQ(t.result.exit_code, 1) << t.result.output;
  EXPECT_LT(t.seconds, 25.0) << t.result.output;
  EXPECT_GE(t.seconds, 6.0) << "the start is allowed 3 x stall_timeout: " << t.result.output;
  EXPECT_TRUE(has(t.result.output, "process 'plant' exited with code 1")) << t.result.output;
  EXPECT_TRUE(has(t.result.output, "stalled at tick 0: no ACTUATOR_STATE answered it in 6"))
      << t.result.output;
  EXPECT_TRUE(has(t.result.output, "no valid CONTROL_COMMAND for tick 0 reached the actuator"))
      << t.result.output;
  EXPECT_TRUE(has(t.result.output, "the controller was never heard")) << t.result.output;
}

// The project's own controller in the external slot, but signing with a key
// of its own: every command it sends fails the MAC at the actuator, and the
// diagnosis says so with the count.
TEST(Stall, AControllerWithTheWrongKeyIsNamedWithItsRejectedCommands) {
  const std::string dir = freshDir("stall-wrong-key");
  std::filesystem::create_directories(dir);
  const std::string key = dir + "/other.key";
  ASSERT_EQ(lagrange("keygen " + quote(key)).exit_code, 0);
  // The controller, joining the run as an external program would, but with the other key.
  const std::string wrapper = dir + "/controller.sh";
  std::ofstream(wrapper) << "#!/bin/sh\nexec " << kBin << "/lagrange-controller --config " << quote(kRigid)
                         << " --lcm-url \"$LAGRANGE_LCM_URL\" --run-id \"$LAGRANGE_RUN_ID\" --key-file "
                         << quote(key) << "\n";
  std::filesystem::permissions(wrapper, std::filesystem::perms::owner_all);
  const std::string command = "[" + wrapper + "]";
  const std::string out = dir + "/run";
  const Timed t = timedRun(out, "--set \"controller={type: external, command: " + command + "}\"");
  EXPECT_EQ(t.result.exit_code, 1) << t.result.output;
  EXPECT_LT(t.seconds, 25.0) << t.result.output;
  EXPECT_TRUE(has(t.result.output,
                  "no valid CONTROL_COMMAND for tick 0 reached the actuator (it accepted 0 "
                  "CONTROL_COMMAND and rejected"))
      << t.result.output;
  EXPECT_TRUE(has(t.result.output, "unauthenticated")) << t.result.output;
  // The key file of the run is gone with it; the user's own is left alone.
  EXPECT_FALSE(std::filesystem::exists(out + "/run.key"));
  EXPECT_TRUE(std::filesystem::exists(key));
}

// A restarted controller loads and checks its gains before it answers; the
// launcher tells the plant (SIGCONT) and the plant's wait gets the start-up
// allowance. The restarted program here takes 4.5 s to start: past
// stall_timeout (3 s), within the allowance (9 s). Without the notice the
// plant would stop the run 3 s after the kill.
TEST(Stall, ARestartedControllerGetsTheStartUpAllowance) {
  const std::string dir = freshDir("stall-restart");
  std::filesystem::create_directories(dir);
  const std::string config = dir + "/run-controller.yaml";  // puts dir/run on its command line
  std::filesystem::copy_file(kRigid, config);
  const std::string wrapper = dir + "/controller.sh";
  std::ofstream(wrapper) << "#!/bin/sh\n"
                         << "if [ -e " << quote(dir + "/started") << " ]; then sleep 4.5; fi\n"
                         << "touch " << quote(dir + "/started") << "\n"
                         << "exec " << kBin << "/lagrange-controller --config " << quote(config)
                         << " --set duration=5 --lcm-url \"$LAGRANGE_LCM_URL\" --run-id \"$LAGRANGE_RUN_ID\""
                         << " --key-file \"$LAGRANGE_KEY_FILE\"\n";
  std::filesystem::permissions(wrapper, std::filesystem::perms::owner_all);
  const SignalledRun run = signalMidRun(
      dir + "/run", kRigid, "lagrange-controller", SIGKILL,
      "-q --set duration=5 --set lockstep.stall_timeout=3 --set supervision.restart=[controller] "
      "--set \"controller={type: external, command: [" +
          wrapper + "]}\"",
      300'000);
  ASSERT_TRUE(run.signalled) << run.result.output;
  EXPECT_EQ(run.result.exit_code, 0) << run.result.output;
  EXPECT_TRUE(has(run.result.output, "restarting it (restart 1")) << run.result.output;
  const auto j = readSummary(dir + "/run");
  EXPECT_EQ(j["supervision"]["restarts"]["controller"], 1) << j["supervision"].dump();
  EXPECT_EQ(j["tracking"]["samples"], 5001);
}

}  // namespace
}  // namespace lagrange::testing
