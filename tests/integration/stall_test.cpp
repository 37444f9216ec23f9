// Nothing waits forever (lockstep.stall_timeout, plant/stall_diagnosis.hpp):
// a controller that never answers, or whose every command fails the check,
// stops the run with exit 1 within the deadline, and the plant's last words
// name whom it waited for, on which channel, and what was seen instead.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "support/launch.hpp"
#include "support/run_log.hpp"

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

}  // namespace
}  // namespace lagrange::testing
