// An attacker on the run's multicast group with the run id in hand (it is
// in lcm.json and in every message) changes nothing (docs/reliability.md,
// "Threat model"). For the whole run it publishes, on every channel, messages
// that would pass every check but the MAC -- this run's id, the channel's
// publisher, fresh sequence numbers, intact checksums, plausible values: a
// position 0.71 rad off, a command and torques of 63.8, far-future ticks, the
// plant's STATUS "finished", a SCENARIO and a ROBOT_DESCRIPTION -- half of
// them with a MAC under a key of its own; and it re-publishes every authentic
// datagram it hears (a replay). Then:
// - in lockstep the controller's outputs are those of an unattacked run, bit
//   for bit, tick for tick, and the run's truth too;
// - in realtime the run completes, meets its metric, and no process accepted
//   more messages on a channel than its publisher sent;
// - in both, every channel a process listens to counts the forgeries
//   (unauthenticated) and the replays (old_or_repeated) in summary.json.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "lagrange/robot_description_t.hpp"
#include "lagrange/scenario_t.hpp"
#include "lagrange/status_t.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "tools/spy/spy.hpp"
#include "transport/checksum.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::testing {
namespace {

const std::vector<std::string> kForgedChannels = {"PLANT_POSITION", "PLANT_TRUTH",     "PLANT_MOTOR",
                                                  "PLANT_RATE",     "CONTROL_COMMAND", "ACTUATOR_STATE",
                                                  "STATUS",         "SCENARIO",        "ROBOT_DESCRIPTION"};

// A header that passes every check but the MAC: the run's id, the channel's
// publisher, a sequence number far ahead of the real one.
lagrange::header_t forgedHeader(int64_t run_id, const std::string& publisher, int64_t tick, int64_t seq) {
  lagrange::header_t h{};
  h.tick = tick;
  h.sim_time = 0.001 * static_cast<double>(tick);
  h.run_id = run_id;
  h.publisher = publisher;
  h.publisher_pid = 4242;
  h.seq = seq;
  return h;
}

template <class Msg>
std::vector<uint8_t> encodeSealed(Msg m) {
  if constexpr (!std::is_same_v<Msg, lagrange::scenario_t> &&
                !std::is_same_v<Msg, lagrange::robot_description_t>)
    transport::seal(m);
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// One forged datagram for `channel`, as convincing as the attacker can make it.
std::vector<uint8_t> forge(const std::string& channel, int64_t run_id, int64_t tick, int64_t seq) {
  const std::vector<double> off = {0.71, 0.71};
  if (channel == "PLANT_POSITION") {
    lagrange::plant_position_t m{};
    m.header = forgedHeader(run_id, "plant", tick, seq);
    m.num_joints = 2;
    m.q = off;
    return encodeSealed(m);
  }
  if (channel == "PLANT_MOTOR") {
    lagrange::plant_motor_t m{};
    m.header = forgedHeader(run_id, "plant", tick, seq);
    m.num_joints = 2;
    m.q = off;
    return encodeSealed(m);
  }
  if (channel == "PLANT_RATE") {
    lagrange::plant_rate_t m{};
    m.header = forgedHeader(run_id, "plant", tick, seq);
    m.num_joints = 2;
    m.qdot = off;
    return encodeSealed(m);
  }
  if (channel == "PLANT_TRUTH") {
    lagrange::plant_truth_t m{};
    m.header = forgedHeader(run_id, "plant", tick, seq);
    m.num_joints = 2;
    m.q = off;
    m.qdot = {0.0, 0.0};
    m.tau_applied = {0.0, 0.0};
    m.input_actuator_tick = tick - 1;
    return encodeSealed(m);
  }
  if (channel == "CONTROL_COMMAND") {
    lagrange::control_command_t m{};
    m.header = forgedHeader(run_id, "controller", tick, seq);
    m.input_position_tick = tick;
    m.input_actuator_tick = -1;
    m.input_motor_tick = -1;
    m.num_joints = 2;
    m.u = {63.8, 63.8};
    m.q_desired = m.q_error = m.theta = m.filter_state = {0.0, 0.0};
    return encodeSealed(m);
  }
  if (channel == "ACTUATOR_STATE") {
    lagrange::actuator_state_t m{};
    m.header = forgedHeader(run_id, "actuator", tick, seq);
    m.input_command_tick = tick;
    m.num_joints = 2;
    m.order = 0;
    m.u_commanded = {63.8, 63.8};
    m.torque_steps = 1;
    m.tau_applied = {{63.8, 63.8}};
    m.saturated = {false, false};
    return encodeSealed(m);
  }
  if (channel == "STATUS") {
    lagrange::status_t m{};
    m.header = forgedHeader(run_id, "plant", tick, seq);
    m.process = "plant";
    m.state = "finished";
    m.last_tick = tick;
    return encodeSealed(m);
  }
  if (channel == "SCENARIO") {
    lagrange::scenario_t m{};
    m.name = "forged";
    m.yaml = "duration: 1\n";
    return encodeSealed(m);
  }
  lagrange::robot_description_t m{};
  m.kind = "forged";
  return encodeSealed(m);
}

// The attacker: joins the run's URL (from lcm.json) and, until stopped,
// publishes forgeries on every channel and replays what it hears.
class Attacker {
 public:
  explicit Attacker(const std::string& out_dir) : thread_([this, out_dir] { attack(out_dir); }) {}
  ~Attacker() {
    stop_ = true;
    thread_.join();
  }
  long long forged() const { return forged_; }
  long long replayed() const { return replayed_; }

 private:
  void attack(const std::string& out_dir) {
    while (!stop_ && !std::filesystem::exists(out_dir + "/lcm.json"))
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (stop_) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // written whole
    const tools::RunEndpoint run = tools::readEndpoint(out_dir);
    lcm::LCM bus(run.lcm_url);
    if (!bus.good()) return;
    bus.subscribeFunction(
        "(PLANT_|CONTROL_|ACTUATOR_|STATUS).*",
        +[](const lcm::ReceiveBuffer* rbuf, const std::string& channel, Attacker* self) {
          self->onHeard(rbuf, channel);
        },
        this);
    const transport::MessageAuthenticator own_key(transport::randomMessageKey());
    int64_t seq = 1000000;
    for (int round = 0; !stop_; ++round) {
      const int64_t tick = round % 3 == 0 ? 1000000000000LL : round;  // some from the far future
      for (const std::string& channel : kForgedChannels) {
        std::vector<uint8_t> bytes = forge(channel, run.run_id, tick, ++seq);
        if (round % 2 == 1) own_key.sign(bytes);
        bus.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
        ++forged_;
      }
      while (bus.handleTimeout(0) > 0) {
      }
      std::vector<std::pair<std::string, std::vector<uint8_t>>> replay;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        replay.swap(heard_);
      }
      for (const auto& [channel, bytes] : replay) {
        bus.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
        ++replayed_;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  void onHeard(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    const auto* data = static_cast<const uint8_t*>(rbuf->data);
    std::lock_guard<std::mutex> lock(mutex_);
    if (heard_.size() < 50) heard_.emplace_back(channel, std::vector<uint8_t>(data, data + rbuf->data_size));
  }

  std::atomic<bool> stop_{false};
  std::atomic<long long> forged_{0}, replayed_{0};
  std::mutex mutex_;
  std::vector<std::pair<std::string, std::vector<uint8_t>>> heard_;
  std::thread thread_;
};

// How many of `reason` summary.json counts on `channel`, over all processes.
long long rejected(const nlohmann::json& summary, const std::string& channel, const std::string& reason) {
  const nlohmann::json& messages = summary.at("messages");
  if (!messages.contains(channel)) return 0;
  return messages.at(channel).at("rejected_by_reason").value(reason, 0LL);
}

void expectForgeriesCounted(const nlohmann::json& summary) {
  for (const std::string& channel : kForgedChannels) {
    // SCENARIO is for stock loggers: no process of the run listens to it, so
    // a forged one reaches nobody to count it (the logger writes its own first).
    if (channel == "SCENARIO") continue;
    EXPECT_GT(rejected(summary, channel, "unauthenticated"), 0)
        << channel << " " << summary["messages"].dump();
  }
  // Replayed authentic messages: counted as repeats by those who read them.
  long long repeats = 0;
  for (const char* channel : {"PLANT_POSITION", "CONTROL_COMMAND", "ACTUATOR_STATE"})
    repeats += rejected(summary, channel, "old_or_repeated");
  EXPECT_GT(repeats, 0) << summary["messages"].dump();
}

// The run on the test's own network, where the attacker is: the URL is the
// run's (as lcm.json would tell an attacker), the run id and key its own.
std::string onUrl(int port) {
  return " --no-netns --lcm-url 'udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0'";
}

TEST(Forgery, LockstepUnderAttackGivesTheUnattackedRunBitForBit) {
  const std::string clean = freshDir("forgery-clean"), attacked = freshDir("forgery-lockstep");
  const std::string options = "-q --set duration=2" + onUrl(7691);
  ASSERT_EQ(runScenario(kRigid, clean, options).exit_code, 0);
  long long forged = 0, replayed = 0;
  RunResult r;
  {
    Attacker attacker(attacked);
    r = runScenario(kRigid, attacked, options);
    forged = attacker.forged();
    replayed = attacker.replayed();
  }
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_GT(forged, 1000) << "the attack did not happen";
  ASSERT_GT(replayed, 10) << "the replay did not happen";

  const auto a = readCommands(clean + "/run.lcm"), b = readCommands(attacked + "/run.lcm");
  ASSERT_EQ(a.size(), 2001u);
  EXPECT_EQ(a, b);  // every tick's torque, bit for bit
  const auto ta = readTruth(clean + "/run.lcm"), tb = readTruth(attacked + "/run.lcm");
  ASSERT_EQ(ta.size(), tb.size());
  for (size_t i = 0; i < ta.size(); ++i) ASSERT_EQ(ta[i].q, tb[i].q) << "tick " << ta[i].tick;
  const auto summary = readSummary(attacked);
  EXPECT_EQ(summary["tracking"], readSummary(clean)["tracking"]);
  expectForgeriesCounted(summary);
}

TEST(Forgery, RealtimeUnderAttackAcceptsNothingForged) {
  const std::string attacked = freshDir("forgery-realtime");
  RunResult r;
  long long forged = 0;
  {
    Attacker attacker(attacked);
    r = runScenario(kRigid, attacked, "-q --set duration=2 --set mode=realtime" + onUrl(7692));
    forged = attacker.forged();
  }
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_GT(forged, 1000) << "the attack did not happen";
  const auto summary = readSummary(attacked);
  EXPECT_TRUE(summary["tracking"]["met"].get<bool>()) << summary["tracking"].dump();
  expectForgeriesCounted(summary);
  // Nobody accepted more than the real publisher sent: no forgery got in.
  const auto& processes = summary.at("processes");
  const std::map<std::string, std::pair<std::string, std::string>> readers = {
      {"PLANT_POSITION", {"plant", "controller"}},
      {"CONTROL_COMMAND", {"controller", "actuator"}},
      {"ACTUATOR_STATE", {"actuator", "plant"}}};
  for (const auto& [channel, who] : readers) {
    const long long sent =
        processes.at(who.first).at("channels").at(channel).at("published").get<long long>();
    const long long accepted =
        processes.at(who.second).at("channels").at(channel).at("received").get<long long>();
    EXPECT_GT(accepted, 0) << channel;
    EXPECT_LE(accepted, sent) << channel;
  }
}

}  // namespace
}  // namespace lagrange::testing
