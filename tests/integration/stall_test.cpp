// Nothing waits forever (lockstep.stall_timeout, plant/stall_diagnosis.hpp):
// a controller that never answers, or whose every command fails the check,
// stops the run with exit 1 within the deadline, and the plant's last words
// name whom it waited for, on which channel, and what was seen instead.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <thread>
#include <vector>

#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "support/signal_run.hpp"
#include "tools/spy/spy.hpp"
#include "transport/checksum.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::testing {
namespace {

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
// A run spread over hosts whose plant's host is gone (or never came): the
// logger's host had nobody to stop it, and waited forever (seen: 17 minutes).
// Now the logger stops, naming the plant's silence, and keeps its log.
TEST(Stall, ALoggerWhosePlantIsNeverHeardStopsNamingIt) {
  const std::string out = freshDir("stall-no-plant");
  std::filesystem::create_directories(out);
  const auto start = std::chrono::steady_clock::now();
  const RunResult r = shell(
      kBin + "/lagrange-logger --config " + quote(kRigid) +
      " --set lockstep.stall_timeout=0.5 --lcm-url 'udpm://239.255.76.67:7695?ttl=0' --out " + quote(out));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_LT(seconds, 15.0) << r.output;
  EXPECT_GE(seconds, 3.0) << "before 6 x lockstep.stall_timeout";
  EXPECT_TRUE(has(r.output, "the plant has not been heard for 3 s (3 s at the start is allowed")) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out + "/run.lcm"));
}

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

// A controller that has the key but whose every command fails the checksum:
// the test answers each PLANT_POSITION itself, in the controller's name,
// signed with the run's key (read from OUT/run.key, as an external program
// would) but with a checksum one off. The actuator rejects each as corrupt,
// and the plant's diagnosis counts them.
class BadChecksumController {
 public:
  explicit BadChecksumController(const std::string& out_dir) : thread_([this, out_dir] { serve(out_dir); }) {}
  ~BadChecksumController() {
    stop_ = true;
    thread_.join();
  }
  long long sent() const { return sent_; }

 private:
  void serve(const std::string& out_dir) {
    while (!stop_ &&
           !(std::filesystem::exists(out_dir + "/lcm.json") && std::filesystem::exists(out_dir + "/run.key")))
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (stop_) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // both written whole
    std::ifstream key_in(out_dir + "/run.key");
    std::string hex;
    key_in >> hex;
    transport::MessageKey key{};
    if (!transport::fromHex(hex, key)) return;
    const transport::MessageAuthenticator auth(key);
    const tools::RunEndpoint run = tools::readEndpoint(out_dir);
    lcm::LCM bus(run.lcm_url);
    if (!bus.good()) return;
    struct Context {
      BadChecksumController* self;
      lcm::LCM* bus;
      const transport::MessageAuthenticator* auth;
      int64_t run_id;
      int64_t seq = 0;
    } context{this, &bus, &auth, run.run_id};
    bus.subscribeFunction(
        "PLANT_POSITION",
        +[](const lcm::ReceiveBuffer* rbuf, const std::string&, Context* c) {
          lagrange::plant_position_t p;
          if (p.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) return;
          lagrange::control_command_t m{};
          m.header.tick = p.header.tick;
          m.header.sim_time = p.header.sim_time;
          m.header.run_id = c->run_id;
          m.header.publisher = "controller";
          m.header.publisher_pid = 4242;
          m.header.seq = ++c->seq;
          m.input_position_tick = p.header.tick;
          m.input_actuator_tick = -1;
          m.input_motor_tick = -1;
          m.num_joints = p.num_joints;
          m.u = m.q_desired = m.q_error = m.theta = m.filter_state = std::vector<double>(p.num_joints, 0.0);
          transport::seal(m);
          m.header.checksum += 1;  // the one thing wrong
          std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
          m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
          c->auth->sign(bytes);
          c->bus->publish("CONTROL_COMMAND", bytes.data(), static_cast<unsigned>(bytes.size()));
          ++c->self->sent_;
        },
        &context);
    while (!stop_) bus.handleTimeout(20);
  }

  std::atomic<bool> stop_{false};
  std::atomic<long long> sent_{0};
  std::thread thread_;
};

TEST(Stall, AControllerWhoseCommandsFailTheChecksumIsNamedWithTheirCount) {
  const std::string out = freshDir("stall-checksum");
  Timed t;
  long long sent = 0;
  {
    const BadChecksumController controller(out);
    // On the test's own network (where this thread is), not a private one.
    t = timedRun(out,
                 "--no-netns --lcm-url 'udpm://239.255.76.67:7695?ttl=0' "
                 "--set 'controller={type: external, command: [sleep, \"600\"]}'");
    sent = controller.sent();
  }
  EXPECT_GT(sent, 0) << "the test's controller never answered: " << t.result.output;
  EXPECT_EQ(t.result.exit_code, 1) << t.result.output;
  EXPECT_LT(t.seconds, 25.0) << t.result.output;
  EXPECT_TRUE(
      has(t.result.output,
          "no valid CONTROL_COMMAND for tick 0 reached the actuator (it accepted 0 CONTROL_COMMAND and "
          "rejected"))
      << t.result.output;
  EXPECT_TRUE(has(t.result.output, "corrupt (checksum)")) << t.result.output;
  EXPECT_FALSE(has(t.result.output, "unauthenticated")) << "the MAC was right: " << t.result.output;
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
