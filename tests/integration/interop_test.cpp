// Stock LCM tools work with lagrange: the stock lcm-logplayer plays a log of
// `lagrange run` into a live controller process, which answers with the
// recorded commands bit for bit; and a log the stock lcm-logger records from
// a running scenario is accepted by `lagrange replay` and `lagrange report`.
//
// lcm-logger subscribes with LCM's default queue of 30 messages and cannot be
// told otherwise: when it is not scheduled for the time 30 messages take to
// arrive (12 ms at the logplayer's pace here, under 5 ms in a lockstep run),
// LCM drops the rest for it, silently (the kernel's UDP counters stay at 0).
// So the controller's answers are collected here with a deep queue, and the
// stock logger's recording is taken again when it came out incomplete.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include "lagrange/control_command_t.hpp"
#include "lagrange/scenario_t.hpp"
#include "lagrange/status_t.hpp"
#include "support/child.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/run_log.hpp"
#include "tools/view/view_source.hpp"

namespace lagrange::testing {
namespace {

std::string freshUrl() {
  static std::mt19937 rng(std::random_device{}());
  return "udpm://239.255.76.67:" + std::to_string(20000 + rng() % 20000) + "?ttl=0";
}

// Every event of a log, by channel, in order (an unreadable file: none).
std::vector<std::pair<std::string, std::string>> events(const std::string& path) {
  std::vector<std::pair<std::string, std::string>> out;
  if (!std::filesystem::exists(path)) return out;
  lcm::LogFile log(path, "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* ev = log.readNextEvent())
    out.emplace_back(ev->channel, std::string(static_cast<const char*>(ev->data), ev->datalen));
  return out;
}

using Events = std::vector<std::pair<std::string, std::string>>;

// The commands among events, first copy per tick.
std::map<int64_t, lagrange::control_command_t> commands(const Events& events) {
  std::map<int64_t, lagrange::control_command_t> out;
  for (const auto& [channel, data] : events) {
    lagrange::control_command_t m;
    if (channel == "CONTROL_COMMAND" && m.decode(data.data(), 0, static_cast<int>(data.size())) > 0)
      out.emplace(m.header.tick, m);
  }
  return out;
}

bool heardStatusFrom(const Events& events, const std::string& process) {
  for (const auto& [channel, data] : events) {
    lagrange::status_t m;
    if (channel == "STATUS" && m.decode(data.data(), 0, static_cast<int>(data.size())) > 0 &&
        m.process == process)
      return true;
  }
  return false;
}

// Every message on the channels matching `regex`, kept in memory by a thread
// of its own whose subscription queue holds everything a stall lets pile up.
class Recorder {
 public:
  Recorder(const std::string& url, const std::string& regex) : lcm_(url) {
    // A plain function, not subscribe(..., &Recorder::onMessage, this): GCC 12's
    // UBSan vptr check trips on LCM's member-pointer call (see CMakeLists.txt).
    lcm_.subscribeFunction(regex, &Recorder::onMessage, this)->setQueueCapacity(1000000);
    thread_ = std::thread([this] {
      while (!stop_) lcm_.handleTimeout(20);
    });
  }
  ~Recorder() {
    stop_ = true;
    thread_.join();
  }
  bool good() { return lcm_.good(); }
  Events events() {
    std::lock_guard<std::mutex> lock(mutex_);
    return events_;
  }

 private:
  static void onMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Recorder* self) {
    std::lock_guard<std::mutex> lock(self->mutex_);
    self->events_.emplace_back(channel, std::string(static_cast<const char*>(rbuf->data), rbuf->data_size));
  }
  lcm::LCM lcm_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  Events events_;
  std::thread thread_;
};

// The fewest distinct ticks a log holds on any of the channels replay reads
// (PLANT_POSITION, PLANT_TRUTH, CONTROL_COMMAND, ACTUATOR_STATE).
size_t fewestTicks(const std::string& path) {
  std::map<std::string, std::set<long long>> ticks;
  for (const auto& [channel, tick] : readTicks(path)) ticks[channel].insert(tick);
  size_t fewest = ticks.size() == 4 ? SIZE_MAX : 0;
  for (const auto& [channel, set] : ticks) fewest = std::min(fewest, set.size());
  return fewest;
}

class LogplayerIntoLiveController : public ::testing::TestWithParam<std::string> {};

TEST_P(LogplayerIntoLiveController, AnswersWithTheRecordedCommands) {
  const std::string golden = kGoldenDir + GetParam() + ".lcm";
  const std::string dir = freshDir("logplayer");
  std::filesystem::create_directories(dir);
  const std::string url = freshUrl();

  // The controller's config: the scenario the log carries.
  const auto recorded = events(golden);
  ASSERT_FALSE(recorded.empty());
  ASSERT_EQ(recorded.front().first, "SCENARIO");
  const std::string config = dir + "/scenario.yaml";
  lagrange::scenario_t scenario;
  const std::string& bytes = recorded.front().second;
  ASSERT_GT(scenario.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
  std::ofstream(config) << scenario.yaml;

  Recorder answers(url, "CONTROL_COMMAND|STATUS");
  ASSERT_TRUE(answers.good()) << url;
  Child controller({kBin + "/lagrange-controller", "--config", config, "--lcm-url", url},
                   dir + "/controller.log");
  // Play only once the controller listens: its STATUS "ready" reached the recorder.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!heardStatusFrom(answers.events(), "controller") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(heardStatusFrom(answers.events(), "controller")) << "the controller did not report on " << url;

  // Its inputs, and STATUS (the plant's "finished" ends the controller). At a
  // quarter of the recorded speed: the lockstep run that recorded them went at
  // ~10 000 messages a second, which a loaded machine's socket buffers do not
  // always take (a logplayer has no re-sends; 5 % of the ticks went missing
  // while a build ran beside the test).
  const RunResult play =
      shell("lcm-logplayer --speed=0.25 --lcm-url='" + url +
            "' -e '^(PLANT_POSITION|PLANT_MOTOR|ACTUATOR_STATE|STATUS)$' " + quote(golden));
  EXPECT_EQ(play.exit_code, 0) << play.output;
  EXPECT_EQ(controller.wait(20), 0) << "the controller did not finish after the plant's final STATUS";
  std::this_thread::sleep_for(std::chrono::milliseconds(200));

  const auto expected = commands(events(golden));
  const auto live = commands(answers.events());
  ASSERT_EQ(expected.size(), 1001u);
  EXPECT_EQ(live.size(), expected.size()) << "commands answered by the live controller";
  long long identical = 0;
  for (const auto& [tick, want] : expected) {
    const auto it = live.find(tick);
    if (it == live.end()) continue;
    const auto& got = it->second;
    const bool same = got.u == want.u && got.q_error == want.q_error && got.theta == want.theta &&
                      got.filter_state == want.filter_state && got.xi_error == want.xi_error &&
                      got.input_actuator_tick == want.input_actuator_tick;
    EXPECT_TRUE(same) << "tick " << tick << ": the live command differs from the recorded one";
    identical += same;
    if (!same) break;
  }
  EXPECT_EQ(identical, 1001);
}

INSTANTIATE_TEST_SUITE_P(GoldenLogs, LogplayerIntoLiveController,
                         ::testing::Values("rigid_2dof_lockstep", "chain_m2_lockstep"));

// A stock lcm-logger, started before the run on the run's LCM URL, records a
// log that lagrange replay, report and view accept: the logger publishes
// the scenario on SCENARIO and the arm on ROBOT_DESCRIPTION.
TEST(StockLogger, ItsRecordingOfARunReplaysAndReports) {
  const std::string dir = freshDir("stock-logger");
  std::filesystem::create_directories(dir);
  const std::string url = freshUrl();
  const std::string log = dir + "/stock.lcm";
  // At most 3 recordings: LCM drops messages for a stalled lcm-logger (see
  // the top of this file); what is tested is that a complete one is accepted.
  size_t recorded = 0;
  for (int attempt = 1; attempt <= 3 && recorded != 1001; ++attempt) {
    Child logger({"lcm-logger", "--lcm-url=" + url, "-f", "--flush-interval=20", log},
                 dir + "/lcm-logger.out");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!std::filesystem::exists(log) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const std::string out = dir + "/run" + std::to_string(attempt);
    const RunResult run = runScenario(std::string(LAGRANGE_SOURCE_DIR) + "/configs/chain_m1.yaml", out,
                                      "-q --set duration=1 --no-netns --lcm-url '" + url + "'");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    logger.signal(SIGINT);
    EXPECT_EQ(logger.wait(10), 0);
    recorded = fewestTicks(log);
    std::printf("recording %d: %zu of 1001 ticks on every channel replay reads\n", attempt, recorded);
    // The run's own logger, in flow control with the plant, missed none.
    EXPECT_EQ(readSummary(out)["log"]["missing_samples"], 0);
  }
  ASSERT_EQ(recorded, 1001u);

  for (const std::string component : {"controller", "actuator", "plant"}) {
    const RunResult r = lagrange("replay " + quote(log) + " --component " + component);
    EXPECT_EQ(r.exit_code, 0) << component << ": " << r.output;
    EXPECT_NE(r.output.find("reproduced all 1001 recorded outputs"), std::string::npos) << r.output;
  }
  const RunResult report = lagrange("report " + quote(log) + " -o " + quote(dir + "/report"));
  EXPECT_EQ(report.exit_code, 0) << report.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/report/tracking_error.png")) << report.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/report/CONTROL_COMMAND.csv")) << report.output;
  // And lagrange view draws it: the logger's ROBOT_DESCRIPTION is in the
  // recording itself (no note that the arm came from SCENARIO).
  const tools::ViewLog view = tools::readViewLog(log);
  EXPECT_EQ(view.description.kind, "planar_chain");
  EXPECT_TRUE(view.notes.empty()) << view.notes.front();
  EXPECT_EQ(view.frames.size(), 1001u);
}

}  // namespace
}  // namespace lagrange::testing
