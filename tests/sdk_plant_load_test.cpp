// The C++ SDK's plant (lagrange::sdk::servePlant) under load and in lockstep
// (issue #52, items 7 and 8), over real LCM in a network namespace of its own
// (own_netns.sh): this test plays the actuator and the logger on a thread of
// its own. No timing is asserted: a step() that sleeps two periods makes
// the loop late for certain, and what is asserted is what the plant did
// about it -- it still reads every answer and applies the newest fresh
// torque (the Python twin: tests/python_plant_helpers_test.py) -- and that
// in lockstep a late answer never brakes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "lagrange/sdk/external_plant.hpp"
#include "lagrange/status_t.hpp"
#include "sdk/contract.hpp"

namespace lagrange::testing {
namespace {

std::vector<double> torqueOf(int64_t tick) {  // tells which tick's answer was applied
  return {static_cast<double>(tick), -static_cast<double>(tick)};
}

// The run's environment for the plant and for the fake peers: a bus private to
// this namespace, a key file of its own.
void setRunEnvironment(const std::string& mode) {
  const std::string key = "/tmp/lagrange_sdk_plant_load_" + std::to_string(getpid()) + ".key";
  std::ofstream(key) << std::string(64, 'a') << "\n";
  setenv("LAGRANGE_LCM_URL", "udpm://239.255.76.91:7691?ttl=0", 1);
  setenv("LAGRANGE_RUN_ID", "7", 1);
  setenv("LAGRANGE_KEY_FILE", key.c_str(), 1);
  setenv("LAGRANGE_JOINTS", "2", 1);
  setenv("LAGRANGE_MODE", mode.c_str(), 1);
}

sdk::PlantScenario scenarioOf(const std::string& mode, double duration) {
  sdk::PlantScenario s;
  s.mode = mode;
  s.publish_rate = 1000.0;
  s.duration = duration;
  s.retransmit_timeout = 0.02;
  s.logger_window = 50;
  s.stall_timeout = 5.0;
  s.max_torque_age = 2;
  s.hold_periods = 0;
  s.hold = false;
  s.q0 = {0.0, 0.0};
  s.qdot0 = {0.0, 0.0};
  return s;
}

/// The actuator and the logger: every position answered with its tick's
/// ACTUATOR_STATE (but the first copy of a tick in `late`: only its re-sent
/// copy is; none at all without `answer`), every PLANT_TRUTH confirmed by the logger's STATUS; the
/// plant's own PLANT_TRUTH and final STATUS kept.
class FakePeers {
 public:
  explicit FakePeers(std::set<int64_t> late = {}, bool answer = true)
      : late_(std::move(late)), answer_(answer), bus_("actuator") {
    bus_.lcm().subscribe("PLANT_POSITION", &FakePeers::onPosition, this);
    bus_.lcm().subscribe("PLANT_TRUTH", &FakePeers::onTruth, this);
    bus_.lcm().subscribe("STATUS", &FakePeers::onStatus, this);
    thread_ = std::thread([this] { serve(); });
  }
  ~FakePeers() {
    stop_ = true;
    thread_.join();
  }
  FakePeers(const FakePeers&) = delete;
  FakePeers& operator=(const FakePeers&) = delete;

  std::vector<lagrange::plant_truth_t> truth() {
    std::lock_guard<std::mutex> lock(mutex_);
    return truth_;
  }
  std::vector<lagrange::status_t> plantStatus() {
    std::lock_guard<std::mutex> lock(mutex_);
    return plant_status_;
  }
  int copiesOf(int64_t tick) {
    std::lock_guard<std::mutex> lock(mutex_);
    return copies_.count(tick);
  }

 private:
  void serve() {
    auto next_hello = std::chrono::steady_clock::now();
    while (!stop_) {
      // A realtime plant starts once it heard these (and drops what came before it listened).
      if (std::chrono::steady_clock::now() >= next_hello) {
        for (const char* process : {"logger", "controller", "actuator"}) status(process, -1);
        next_hello += std::chrono::milliseconds(50);
      }
      bus_.handle(5);
    }
  }

  void status(const std::string& process, int64_t last_tick) {
    lagrange::status_t s{};
    s.process = process;
    s.state = "running";
    s.last_tick = last_tick;
    s.message = "";
    s.num_channels = 0;
    bus_.publish("STATUS", s, std::max<int64_t>(last_tick, 0), 0.0);
  }

  template <class Msg>
  bool take(const lcm::ReceiveBuffer* rbuf, Msg& m) {
    return bus_.receive(rbuf, m) == sdk::contract::Verdict::kAccepted && m.header.publisher == "plant";
  }

  void onPosition(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    lagrange::plant_position_t p;
    if (!take(rbuf, p)) return;
    const int64_t k = p.header.tick;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      copies_.insert(k);
      if (!answer_ || (late_.count(k) && copies_.count(k) == 1)) return;  // late: answered when re-sent
    }
    lagrange::actuator_state_t a{};
    a.input_command_tick = k;
    a.num_joints = 2;
    a.order = 0;
    a.u_commanded = torqueOf(k);
    a.torque_steps = 1;
    a.tau_applied = {torqueOf(k)};
    a.saturated = {false, false};
    bus_.publish("ACTUATOR_STATE", a, k, p.header.sim_time);
  }

  void onTruth(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    lagrange::plant_truth_t t;
    if (!take(rbuf, t)) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      truth_.push_back(t);
    }
    status("logger", t.header.tick);
  }

  void onStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    lagrange::status_t s;
    if (!take(rbuf, s)) return;
    std::lock_guard<std::mutex> lock(mutex_);
    plant_status_.push_back(s);
  }

  std::set<int64_t> late_;
  bool answer_;
  sdk::contract::Bus bus_;
  std::mutex mutex_;
  std::multiset<int64_t> copies_;
  std::vector<lagrange::plant_truth_t> truth_;
  std::vector<lagrange::status_t> plant_status_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

sdk::PlantState still() { return {{0.0, 0.0}, {0.0, 0.0}}; }

TEST(SdkPlantLoad, APlantTwoPeriodsLateEveryTickStillAppliesEachFreshTorque) {
  setRunEnvironment("realtime");
  FakePeers peers;
  const double duration = 0.1;  // 100 ticks at 1 kHz
  const int code = sdk::servePlant(
      [](double, const std::vector<double>&, double) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));  // two periods
        return still();
      },
      {}, [&] { return scenarioOf("realtime", duration); });
  ASSERT_EQ(code, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the last datagrams, on their way
  const auto statuses = peers.plantStatus();
  ASSERT_FALSE(statuses.empty());
  const lagrange::status_t& end = statuses.back();
  ASSERT_EQ(end.state, "finished");
  const auto& loop = end.loop;
  const int64_t ticks = 100;
  // The fault happened: the loop ran past its deadlines, tick after tick.
  EXPECT_GE(loop.deadline_misses, ticks / 2) << "step() sleeps 2 periods: the loop must be late";
  EXPECT_GE(loop.longest_miss_run, ticks / 2);
  // ... and the rule held: the answers were read although each period was
  // over, so the torque stayed fresh (UDP and a thread on a busy machine may
  // deliver one late now and then: a tenth of the periods is allowed).
  EXPECT_LE(loop.torque_zeroed, ticks / 10) << "the torque went stale while behind schedule";
  int commanded = 0;
  for (const auto& t : peers.truth())
    if (t.header.tick > 0 && t.torque_source == lagrange::plant_truth_t::TORQUE_COMMANDED &&
        t.tau_applied == torqueOf(t.input_actuator_tick) && t.header.tick - t.input_actuator_tick <= 2)
      ++commanded;
  EXPECT_GE(commanded, ticks * 9 / 10) << "each period applies a fresh answer";
  // Latency and input age measured: finite numbers, not the NaN of "not measured".
  EXPECT_TRUE(std::isfinite(loop.latency_p50) && loop.latency_p50 >= 0.0);
  EXPECT_TRUE(std::isfinite(loop.input_age_p50) && loop.input_age_p50 >= 0.0);
}

TEST(SdkPlantLoad, InLockstepAnAnswerLateByManyWatchdogPeriodsDoesNotBrake) {
  setRunEnvironment("lockstep");
  FakePeers peers({5});  // tick 5 answered only when re-sent, 20 ms (20 periods) late
  int brakes = 0;
  sdk::PlantOptions options;
  options.watchdog_periods = 2;
  options.brake = [&] { ++brakes; };
  const int code = sdk::servePlant([](double, const std::vector<double>&, double) { return still(); },
                                   options, [&] { return scenarioOf("lockstep", 0.01); });
  ASSERT_EQ(code, 0);
  EXPECT_GE(peers.copiesOf(5), 2) << "tick 5 was answered late (re-sent)";
  EXPECT_EQ(brakes, 0) << "no brake in lockstep: waiting is the protocol";
}

TEST(SdkPlantLoad, WithoutAnswersLatencyAndInputAgeAreNaNNeverZero) {
  // Nothing answered: nothing measured, which loop_stats_t says with NaN
  // (summary.json: null), not with 0 s, a latency too good to be true.
  setRunEnvironment("realtime");
  FakePeers peers({}, /*answer=*/false);
  ASSERT_EQ(sdk::servePlant([](double, const std::vector<double>&, double) { return still(); }, {},
                            [&] { return scenarioOf("realtime", 0.02); }),
            0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const auto statuses = peers.plantStatus();
  ASSERT_FALSE(statuses.empty());
  const auto& loop = statuses.back().loop;
  EXPECT_EQ(statuses.back().state, "finished");
  EXPECT_EQ(loop.torque_zeroed, 19);  // ticks 1 to 19: the last tick, 20, applies nothing
  EXPECT_TRUE(std::isnan(loop.latency_p50) && std::isnan(loop.latency_p99) && std::isnan(loop.latency_max));
  EXPECT_TRUE(std::isnan(loop.input_age_p50) && std::isnan(loop.input_age_p99) &&
              std::isnan(loop.input_age_max));
  EXPECT_TRUE(std::isfinite(loop.jitter_p50)) << "the loop's own timing is measured";
}

}  // namespace
}  // namespace lagrange::testing
