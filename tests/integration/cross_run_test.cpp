// Issue #44's first attack: one run's traffic, recorded off the wire as a
// stock LCM recorder would (every datagram with its MAC trailer), re-sent
// into another run that uses the same key file -- the documented multi-host
// deployment makes one key and reuses it -- and the same run id. Before the
// run key was bound to a value fresh for each run, the second run's plant
// applied the first run's torques and ended 5.3 rad off its reference, while
// it exited 0, `met: true`, with the first run's error and 0 rejections.
// Now the second run is bit for bit an unattacked run, every re-sent
// datagram that reached a process is counted as unauthenticated, and its log
// holds none of them. Two ways: one launcher with --key-file and --run-id,
// and the multi-host deployment (two `--processes` launchers, run id by
// default), where the recorded launchers' own agreement is re-sent too.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "transport/channels.hpp"

namespace lagrange::testing {
namespace {

using Datagram = std::pair<std::string, std::vector<uint8_t>>;

// Every datagram on the URL, as it was on the wire, until destroyed.
class WireRecorder {
 public:
  explicit WireRecorder(const std::string& url) : thread_([this, url] { record(url); }) {}
  ~WireRecorder() { stop(); }
  std::vector<Datagram> stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    return heard_;
  }

 private:
  void record(const std::string& url) {
    lcm::LCM bus(url);
    if (!bus.good()) return;
    bus.subscribeFunction(
           ".*",
           +[](const lcm::ReceiveBuffer* rbuf, const std::string& channel, WireRecorder* self) {
             const auto* data = static_cast<const uint8_t*>(rbuf->data);
             std::lock_guard<std::mutex> lock(self->mutex_);
             self->heard_.emplace_back(channel, std::vector<uint8_t>(data, data + rbuf->data_size));
           },
           this)
        ->setQueueCapacity(1000000);
    while (!stop_) bus.handleTimeout(20);
  }
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::vector<Datagram> heard_;
  std::thread thread_;
};

// Re-sends a recording onto the URL, over and over, until destroyed, at
// about 5 000 datagrams a second -- the pace of the run's own traffic: an
// attack on what a run accepts, not a flood (availability is not what the
// MAC promises; docs/reliability.md).
class Replayer {
 public:
  Replayer(const std::string& url, std::vector<Datagram> recording)
      : recording_(std::move(recording)), thread_([this, url] { replay(url); }) {}
  ~Replayer() {
    stop_ = true;
    thread_.join();
  }
  long long sent() const { return sent_; }
  std::map<std::string, long long> sentPerChannel() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return per_channel_;
  }

 private:
  void replay(const std::string& url) {
    lcm::LCM bus(url);
    if (!bus.good()) return;
    while (!stop_) {
      for (const auto& [channel, bytes] : recording_) {
        if (stop_) break;
        bus.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
        if (++sent_ % 5 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        std::lock_guard<std::mutex> lock(mutex_);
        ++per_channel_[channel];
      }
    }
  }
  std::vector<Datagram> recording_;
  std::atomic<bool> stop_{false};
  std::atomic<long long> sent_{0};
  mutable std::mutex mutex_;
  std::map<std::string, long long> per_channel_;
  std::thread thread_;
};

long long rejected(const nlohmann::json& summary, const std::string& channel, const std::string& reason) {
  const nlohmann::json& m = summary.at("messages");
  return m.contains(channel) ? m.at(channel).at("rejected_by_reason").value(reason, 0LL) : 0;
}

// The processes (name and pid) whose messages a log holds on the per-tick channels.
std::set<std::pair<std::string, int32_t>> publishersIn(const std::string& log_path) {
  std::set<std::pair<std::string, int32_t>> out;
  lcm::LogFile log(log_path, "r");
  while (const lcm::LogEvent* ev = log.readNextEvent())
    transport::withChannelMessage(ev->channel, false, [&](auto message) {
      if (logs::decodeEvent(*ev, message))
        out.emplace(message.header.publisher, message.header.publisher_pid);
      return true;
    });
  return out;
}

// B is A, bit for bit, and counted what it refused of A.
void expectUnmovedByTheReplay(const std::string& a_dir, const std::string& b_dir, long long resent) {
  ASSERT_GT(resent, 2000) << "the replay did not happen";
  const auto a = readCommands(a_dir + "/run.lcm"), b = readCommands(b_dir + "/run.lcm");
  ASSERT_EQ(a.size(), 1001u);
  EXPECT_EQ(a, b);  // every tick's torque, bit for bit
  const auto ta = readTruth(a_dir + "/run.lcm"), tb = readTruth(b_dir + "/run.lcm");
  ASSERT_EQ(ta.size(), tb.size());
  for (size_t i = 0; i < ta.size(); ++i) ASSERT_EQ(ta[i].q, tb[i].q) << "tick " << ta[i].tick;
  const nlohmann::json summary = readSummary(b_dir);
  EXPECT_EQ(summary["tracking"], readSummary(a_dir)["tracking"]);
  EXPECT_EQ(summary["status"], "completed");
  // Counted by every process that listens to the channel.
  std::cout << "re-sent " << resent << " datagrams of run A; rejected as unauthenticated:";
  for (const char* channel :
       {"PLANT_POSITION", "PLANT_TRUTH", "CONTROL_COMMAND", "ACTUATOR_STATE", "STATUS"}) {
    EXPECT_GT(rejected(summary, channel, "unauthenticated"), 50)
        << channel << " " << summary["messages"].dump();
    std::cout << " " << channel << " " << rejected(summary, channel, "unauthenticated");
  }
  std::cout << "\n";
  // The log holds B's own messages only: not one from a process of A.
  const auto of_a = publishersIn(a_dir + "/run.lcm"), of_b = publishersIn(b_dir + "/run.lcm");
  ASSERT_EQ(of_a.size(), 3u);  // plant, controller, actuator
  ASSERT_EQ(of_b.size(), 3u);
  for (const auto& p : of_b) EXPECT_EQ(of_a.count(p), 0u) << p.first << " " << p.second;
}

TEST(CrossRun, ARecordedRunResentIntoAnotherWithTheSameKeyFileAndRunIdChangesNothing) {
  const std::string base = freshDir("cross-run");
  std::filesystem::create_directories(base);
  const std::string key = base + "/shared.key";
  ASSERT_EQ(lagrange("keygen " + quote(key)).exit_code, 0);
  const std::string url = "udpm://239.255.76.67:7693?ttl=0";
  const std::string options =
      "-q --set duration=1 --no-netns --lcm-url '" + url + "' --key-file " + quote(key) + " --run-id 777";
  std::vector<Datagram> recording;
  {
    WireRecorder recorder(url);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_EQ(runScenario(kRigid, base + "/a", options).exit_code, 0);
    recording = recorder.stop();
  }
  RunResult b;
  long long resent = 0;
  {
    Replayer replayer(url, recording);
    b = runScenario(kRigid, base + "/b", options);
    resent = replayer.sent();
  }
  ASSERT_EQ(b.exit_code, 0) << b.output;
  expectUnmovedByTheReplay(base + "/a", base + "/b", resent);
  EXPECT_EQ(readSummary(base + "/b")["run_id"], 777);
}

// The same attack on the deployment over hosts: each run is two launchers
// (--processes) that agree on the run first; the run id is the default.
// The recording holds run A's RUN_JOIN messages too: re-sent while B's
// launchers meet, they are never taken for a launcher of B.
TEST(CrossRun, ARecordedSpreadRunResentIntoTheNextOneWithTheSameKeyFileChangesNothing) {
  const std::string base = freshDir("cross-run-spread");
  std::filesystem::create_directories(base);
  const std::string key = base + "/shared.key";
  ASSERT_EQ(lagrange("keygen " + quote(key)).exit_code, 0);
  const std::string url = "udpm://239.255.76.67:7694?ttl=0";
  const std::string options = "--set duration=1 --no-netns --lcm-url '" + url + "' --key-file " + quote(key);
  auto spreadRun = [&](const std::string& tag) {
    RunResult plant_side;
    std::thread other([&] {
      plant_side = runScenario(kRigid, base + "/" + tag + "-plant", options + " --processes plant,actuator");
    });
    const RunResult logger_side =
        runScenario(kRigid, base + "/" + tag, options + " --processes controller,logger");
    other.join();
    return std::make_pair(plant_side, logger_side);
  };
  std::vector<Datagram> recording;
  {
    WireRecorder recorder(url);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const auto [plant_side, logger_side] = spreadRun("a");
    ASSERT_EQ(plant_side.exit_code, 0) << plant_side.output;
    ASSERT_EQ(logger_side.exit_code, 0) << logger_side.output;
    recording = recorder.stop();
  }
  std::vector<Datagram> join_datagrams;
  for (const Datagram& d : recording)
    if (d.first == "RUN_JOIN") join_datagrams.push_back(d);
  const long long joins = static_cast<long long>(join_datagrams.size());
  ASSERT_GT(joins, 0) << "the recording holds no agreement to re-send";
  // A's agreement again every 200 datagrams (about 40 ms at the replayer's
  // pace), so that it is in the air whenever B's launchers meet -- on a fast
  // machine B is over before the replay has gone once through A's 4 000.
  std::vector<Datagram> resending;
  for (size_t i = 0; i < recording.size(); ++i) {
    resending.push_back(recording[i]);
    if (i % 200 == 199) resending.insert(resending.end(), join_datagrams.begin(), join_datagrams.end());
  }
  long long resent = 0;
  std::map<std::string, long long> per_channel;
  std::pair<RunResult, RunResult> b;
  {
    Replayer replayer(url, resending);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // A's agreement in the air first
    b = spreadRun("b");
    resent = replayer.sent();
    per_channel = replayer.sentPerChannel();
  }
  ASSERT_EQ(b.first.exit_code, 0) << b.first.output;
  ASSERT_EQ(b.second.exit_code, 0) << b.second.output;
  EXPECT_NE(b.second.output.find("the launchers agreed"), std::string::npos) << b.second.output;
  EXPECT_GT(per_channel["RUN_JOIN"], joins) << "A's agreement was not re-sent during B's";
  expectUnmovedByTheReplay(base + "/a", base + "/b", resent);
  // Each run its own id, though URL, scenario and key file are the same.
  EXPECT_NE(readSummary(base + "/a")["run_id"], readSummary(base + "/b")["run_id"]);
}

// Launchers of one URL and key file whose scenarios differ (another file, or
// other --set overrides) meet and refuse each other, naming the other's host
// and pid -- rather than each waiting out --join-timeout for nobody.
TEST(CrossRun, LaunchersOfDifferentScenariosRefuseEachOtherNamingTheOther) {
  const std::string base = freshDir("cross-run-two-scenarios");
  std::filesystem::create_directories(base);
  const std::string key = base + "/shared.key";
  ASSERT_EQ(lagrange("keygen " + quote(key)).exit_code, 0);
  const std::string options = "-q --no-netns --lcm-url 'udpm://239.255.76.67:7696?ttl=0' --key-file " +
                              quote(key) + " --join-timeout 20";
  RunResult plant_side;
  std::thread other([&] {
    plant_side = runScenario(kRigid, base + "/p", options + " --set duration=1 --processes plant,actuator");
  });
  const RunResult logger_side =
      runScenario(kRigid, base + "/l", options + " --set duration=2 --processes controller,logger");
  other.join();
  for (const RunResult* r : std::vector<const RunResult*>{&plant_side, &logger_side}) {
    EXPECT_EQ(r->exit_code, 2) << r->output;
    EXPECT_NE(r->output.find("runs another scenario"), std::string::npos) << r->output;
  }
  EXPECT_NE(plant_side.output.find("the launcher of logger,controller on "), std::string::npos)
      << plant_side.output;
  EXPECT_FALSE(std::filesystem::exists(base + "/l/run.lcm")) << "a process started";
}

}  // namespace
}  // namespace lagrange::testing
