// The C++ SDK's plant guards (sdk/external_plant.cpp), the pure pieces of
// lagrange::sdk::runPlant: the realtime stale-torque rule with its watchdog
// (TorqueChoice, the Python module's and the built-in plant's rule), the
// limits a bridge enforces (PlantLimits: clipping, breaches, their checks),
// which ACTUATOR_STATE answers a tick (ActuatorAnswers), what a state
// given by step() or initial() must hold (PlantState::check), and how
// servePlant ends before any peer is needed (brake() once on every end but
// "finished", STATUS "failed" with the reason).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/sdk/external_plant.hpp"
#include "lagrange/status_t.hpp"

namespace lagrange::testing {
namespace {

using sdk::PlantLimits;
using sdk::TorqueChoice;
using sdk::TorqueSource;

const std::vector<double> kTau{1.5, -0.5};

TEST(SdkPlantGuards, TorqueChoiceCommandsWithinMaxAgeHoldsForHoldPeriodsThenZeroes) {
  TorqueChoice choice(/*max_age=*/2, /*hold_periods=*/3, /*hold=*/true);
  for (const int64_t k : {10, 11, 12}) {
    const auto c = choice.choose(k, 10, kTau, 2);
    EXPECT_EQ(c.source, TorqueSource::kCommanded) << "tick " << k;
    EXPECT_EQ(c.tau, kTau);
    EXPECT_EQ(c.input_tick, 10);
  }
  for (const int64_t k : {13, 14, 15}) {
    const auto c = choice.choose(k, 10, kTau, 2);
    EXPECT_EQ(c.source, TorqueSource::kHeld) << "tick " << k;
    EXPECT_EQ(c.tau, kTau);
    EXPECT_EQ(c.input_tick, 10);
  }
  const auto late = choice.choose(16, 10, kTau, 2);
  EXPECT_EQ(late.source, TorqueSource::kZero);
  EXPECT_EQ(late.tau, std::vector<double>(2, 0.0));
  EXPECT_EQ(late.input_tick, -1);
  EXPECT_FALSE(late.tripped_now);
  EXPECT_EQ(choice.held(), 3);
  EXPECT_EQ(choice.zeroed(), 1);
  EXPECT_EQ(choice.watchdogTrips(), 0);
}

TEST(SdkPlantGuards, TorqueChoiceWithoutHoldZeroesPastMaxAge) {
  TorqueChoice choice(2, 3, /*hold=*/false);
  EXPECT_EQ(choice.choose(12, 10, kTau, 2).source, TorqueSource::kCommanded);
  EXPECT_EQ(choice.choose(13, 10, kTau, 2).source, TorqueSource::kZero);
  EXPECT_EQ(choice.held(), 0);
  EXPECT_EQ(choice.zeroed(), 1);
}

TEST(SdkPlantGuards, TorqueChoiceCountsNothingAtTickZero) {
  TorqueChoice choice(2, 3, true, /*watchdog_periods=*/5);
  const auto first = choice.choose(0, std::nullopt, {}, 2);
  EXPECT_EQ(first.source, TorqueSource::kZero);
  EXPECT_EQ(first.tau, std::vector<double>(2, 0.0));
  EXPECT_EQ(choice.zeroed(), 0);
  EXPECT_EQ(choice.held(), 0);
  EXPECT_EQ(choice.watchdogTrips(), 0);
  // No answer by tick 1: a zeroed period, counted.
  EXPECT_EQ(choice.choose(1, std::nullopt, {}, 2).source, TorqueSource::kZero);
  EXPECT_EQ(choice.zeroed(), 1);
}

TEST(SdkPlantGuards, TheWatchdogZeroesBeforeTheHoldLimitAndTripsOncePerSilence) {
  // Hold would keep tick 0's torque to age 2 + 10; the watchdog stops it past 4.
  TorqueChoice choice(2, 10, true, /*watchdog_periods=*/4);
  EXPECT_EQ(choice.choose(4, 0, kTau, 2).source, TorqueSource::kHeld);
  const auto trip = choice.choose(5, 0, kTau, 2);
  EXPECT_EQ(trip.source, TorqueSource::kZero);
  EXPECT_EQ(trip.input_tick, -1);
  EXPECT_TRUE(trip.tripped_now);
  const auto still = choice.choose(6, 0, kTau, 2);
  EXPECT_EQ(still.source, TorqueSource::kZero);
  EXPECT_FALSE(still.tripped_now) << "one trip per silence";
  EXPECT_EQ(choice.watchdogTrips(), 1);
  EXPECT_EQ(choice.zeroed(), 2);
  // An answer ends the silence; the next one trips again.
  EXPECT_EQ(choice.choose(7, 7, kTau, 2).source, TorqueSource::kCommanded);
  EXPECT_FALSE(choice.choose(11, 7, kTau, 2).tripped_now);
  EXPECT_TRUE(choice.choose(12, 7, kTau, 2).tripped_now);
  EXPECT_EQ(choice.watchdogTrips(), 2);
  EXPECT_EQ(choice.held(), 2);  // ticks 4 and 11
}

TEST(SdkPlantGuards, LimitsClipTheTorqueAndSayWhetherTheyDid) {
  PlantLimits limits;
  limits.torque = std::vector<double>{1.0, 2.0};
  const auto [clipped, was] = limits.clip({3.0, -5.0});
  EXPECT_EQ(clipped, (std::vector<double>{1.0, -2.0}));
  EXPECT_TRUE(was);
  const auto [within, was_not] = limits.clip({0.5, -2.0});
  EXPECT_EQ(within, (std::vector<double>{0.5, -2.0}));
  EXPECT_FALSE(was_not);
  const auto [free, unlimited] = PlantLimits{}.clip({30.0, -50.0});
  EXPECT_EQ(free, (std::vector<double>{30.0, -50.0}));
  EXPECT_FALSE(unlimited);
}

TEST(SdkPlantGuards, ABreachNamesJointValueAndLimit) {
  PlantLimits limits;
  limits.position = std::vector<std::pair<double, double>>{{-1.0, 1.0}, {-2.0, 2.0}};
  limits.rate = std::vector<double>{1.0, 4.0};
  EXPECT_EQ(limits.breach({0.5, -2.0}, {-1.0, 4.0}), std::nullopt);
  EXPECT_EQ(limits.breach({0.0, 2.5}, {0.0, 0.0}).value_or(""),
            "joint 2's position 2.5 rad is outside its limits [-2, 2]");
  EXPECT_EQ(limits.breach({0.0, 0.0}, {-3.0, 0.0}).value_or(""),
            "joint 1's rate -3 rad/s is beyond its limit 1");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(limits.breach({nan, 0.0}, {0.0, 0.0}).value_or(""),
            "joint 1's position nan rad is outside its limits [-1, 1]");
  EXPECT_EQ(PlantLimits{}.breach({100.0, nan}, {1e9, nan}), std::nullopt);
}

// Each of the limits' own mistakes, named with what was expected.
std::string limitsError(const PlantLimits& limits, int joints) {
  try {
    limits.check(joints);
  } catch (const sdk::ContractError& e) {
    return e.what();
  }
  return "";
}

TEST(SdkPlantGuards, LimitsThatCannotBeKeptAreRefusedByName) {
  PlantLimits zero_torque;
  zero_torque.torque = std::vector<double>{1.0, 0.0};
  EXPECT_EQ(limitsError(zero_torque, 2), "PlantLimits: every torque limit must be > 0; got [1, 0]");
  PlantLimits upside_down;
  upside_down.position = std::vector<std::pair<double, double>>{{-1.0, 1.0}, {2.0, -2.0}};
  EXPECT_EQ(
      limitsError(upside_down, 2),
      "PlantLimits: every position limit must be {lower, upper} with lower < upper; got [(-1, 1), (2, -2)]");
  PlantLimits one_rate;
  one_rate.rate = std::vector<double>{1.0};
  EXPECT_EQ(limitsError(one_rate, 2), "PlantLimits: 1 rate limits for 2 joints; expected one per joint");
  EXPECT_EQ(limitsError(PlantLimits{}, 2), "");
}

// Lockstep: the first state of the awaited tick answers it, its torque the
// one applied; a stale, repeated or future tick's is ignored.
TEST(SdkPlantGuards, OnlyTheAwaitedTicksFirstStateAnswersIt) {
  sdk::ActuatorAnswers answers;
  EXPECT_FALSE(answers.take(0, kTau, 100)) << "nothing awaited yet";
  EXPECT_FALSE(answers.awaited().has_value());
  answers.await(5);
  EXPECT_FALSE(answers.answered());
  EXPECT_TRUE(answers.answer().empty());
  EXPECT_FALSE(answers.take(4, {9.0, 9.0}, 200)) << "a stale tick's";
  EXPECT_FALSE(answers.take(6, {8.0, 8.0}, 300)) << "a future tick's";
  EXPECT_FALSE(answers.answered());
  EXPECT_TRUE(answers.take(5, kTau, 400));
  EXPECT_TRUE(answers.answered());
  EXPECT_FALSE(answers.take(5, {7.0, 7.0}, 500)) << "a repeated one";
  EXPECT_EQ(answers.answer(), kTau);
  EXPECT_EQ(answers.awaited(), 5);
  // The next tick forgets the answer; tick 6's early state answered nothing.
  answers.await(6);
  EXPECT_FALSE(answers.answered());
  EXPECT_TRUE(answers.answer().empty());
  EXPECT_TRUE(answers.take(6, {1.0, 2.0}, 600));
  EXPECT_EQ(answers.answer(), (std::vector<double>{1.0, 2.0}));
}

// Realtime: the newest state, whichever tick; an older or equal tick's changes nothing.
TEST(SdkPlantGuards, TheNewestStateIsKeptWhicheverTickIsAwaited) {
  sdk::ActuatorAnswers answers;
  EXPECT_FALSE(answers.newestTick().has_value());
  answers.take(3, kTau, 100);
  answers.take(2, {9.0, 9.0}, 200);
  answers.take(3, {8.0, 8.0}, 300);
  EXPECT_EQ(answers.newestTick(), 3);
  EXPECT_EQ(answers.newestTorque(), kTau);
  EXPECT_EQ(answers.newestUtime(), 100);
  answers.await(1);
  EXPECT_FALSE(answers.take(7, {1.0, 2.0}, 400));
  EXPECT_EQ(answers.newestTick(), 7);
  EXPECT_EQ(answers.newestTorque(), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(answers.newestUtime(), 400);
}

std::string stateError(const sdk::PlantState& state, int joints) {
  try {
    state.check(joints, "step() at t = 0.5 s");
  } catch (const sdk::ContractError& e) {
    return e.what();
  }
  return "";
}

TEST(SdkPlantGuards, AStateWithAnInfiniteEnergyIsRefusedByNameAndNaNIsNotKnown) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  sdk::PlantState state{{0.1, 0.2}, {0.0, 0.0}};
  EXPECT_EQ(stateError(state, 2), "") << "energies not given: NaN, not known";
  state.kinetic_energy = 1.5;
  state.potential_energy = nan;
  EXPECT_EQ(stateError(state, 2), "");
  state.kinetic_energy = inf;
  EXPECT_EQ(stateError(state, 2),
            "step() at t = 0.5 s returned inf for kinetic_energy; expected a finite number [J], or NaN (not "
            "known)");
  state.kinetic_energy = 1.0;
  state.potential_energy = -inf;
  EXPECT_EQ(
      stateError(state, 2),
      "step() at t = 0.5 s returned -inf for potential_energy; expected a finite number [J], or NaN (not "
      "known)");
}

TEST(SdkPlantGuards, AStateWithTheWrongCountOrANonFiniteValueIsRefusedByName) {
  EXPECT_EQ(stateError({{0.1}, {0.0, 0.0}}, 2),
            "step() at t = 0.5 s returned 1 numbers for q; expected 2 (one per joint)");
  EXPECT_EQ(stateError({{0.1, 0.2}, {0.0, std::numeric_limits<double>::quiet_NaN()}}, 2),
            "step() at t = 0.5 s returned nan for qdot[1] (joint 2); expected finite numbers");
}

// The environment `lagrange run` gives a plant, for one test; the old values back after it.
class PlantEnvironment {
 public:
  PlantEnvironment() {
    const std::string key_file = ::testing::TempDir() + "sdk_plant_key_" + std::to_string(getpid());
    std::ofstream(key_file) << std::string(64, 'a') << "\n";
    set("LAGRANGE_LCM_URL", url());
    set("LAGRANGE_RUN_ID", "4242");
    set("LAGRANGE_KEY_FILE", key_file);
    set("LAGRANGE_JOINTS", "2");
  }
  ~PlantEnvironment() {
    for (const auto& [name, value] : old_) {
      if (value.second)
        setenv(name.c_str(), value.first.c_str(), 1);
      else
        unsetenv(name.c_str());
    }
  }
  PlantEnvironment(const PlantEnvironment&) = delete;
  PlantEnvironment& operator=(const PlantEnvironment&) = delete;

  // A port of this process's own: ctest runs these tests side by side in one
  // network namespace, and one test's STATUS must never reach another's listener.
  static std::string url() {
    return "udpm://239.255.76.67:" + std::to_string(20000 + getpid() % 40000) + "?ttl=0";
  }

 private:
  void set(const std::string& name, const std::string& value) {
    const char* was = std::getenv(name.c_str());
    old_.emplace_back(name, std::make_pair(std::string(was ? was : ""), was != nullptr));
    setenv(name.c_str(), value.c_str(), 1);
  }
  std::vector<std::pair<std::string, std::pair<std::string, bool>>> old_;
};

sdk::PlantScenario lockstepScenario() {
  sdk::PlantScenario s;
  s.mode = "lockstep";
  s.publish_rate = 1000.0;
  s.duration = 1.0;
  s.retransmit_timeout = 0.05;
  s.logger_window = 10;
  s.stall_timeout = 1.0;
  s.max_torque_age = 2;
  s.hold_periods = 0;
  s.q0 = {0.1, 0.2};
  s.qdot0 = {0.0, 0.0};
  return s;
}

struct Ended {
  int code = -1;
  std::string stderr_text;
  std::vector<std::pair<std::string, std::string>> statuses;  // (state, message) the plant published
};

// servePlant on the lockstep scenario, what it printed and the STATUS it published.
Ended serve(const sdk::PlantOptions& options) {
  PlantEnvironment environment;
  lcm::LCM listener(PlantEnvironment::url());
  EXPECT_TRUE(listener.good());
  Ended ended;
  // Through LCM's C API with a plain function: lcm-cpp's member-handler
  // subscription, on a function-local class, trips UBSan's vptr check.
  struct Collect {
    static void onStatus(const lcm_recv_buf_t* rbuf, const char*, void* user) {
      lagrange::status_t s;
      if (rbuf->data_size > 32 && s.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size - 32)) >= 0 &&
          s.process == "plant")
        static_cast<Ended*>(user)->statuses.emplace_back(s.state, s.message);
    }
  };
  lcm_subscription_t* subscription =
      lcm_subscribe(listener.getUnderlyingLCM(), "STATUS", &Collect::onStatus, &ended);
  const sdk::PlantStep step = [](double, const std::vector<double>&, double) -> sdk::PlantState {
    throw std::logic_error("step() is not reached before a logger answers");
  };
  ::testing::internal::CaptureStderr();
  ended.code = sdk::servePlant(step, options, lockstepScenario);
  ended.stderr_text = ::testing::internal::GetCapturedStderr();
  while (listener.handleTimeout(100) > 0) {
  }
  lcm_unsubscribe(listener.getUnderlyingLCM(), subscription);
  return ended;
}

int countOf(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SdkPlantEnds, AnExceptionFromInitialBrakesOnceAndFailsTheRunWithItsReason) {
  int brakes = 0;
  sdk::PlantOptions options;
  options.brake = [&] { ++brakes; };
  options.initial = []() -> sdk::PlantState { throw std::runtime_error("the arm does not answer"); };
  const Ended ended = serve(options);
  EXPECT_EQ(ended.code, 1);
  EXPECT_EQ(brakes, 1);
  EXPECT_EQ(countOf(ended.stderr_text, "plant: calling brake()"), 1) << ended.stderr_text;
  const std::string why = "initial() failed: the arm does not answer";
  EXPECT_NE(ended.stderr_text.find(why), std::string::npos) << ended.stderr_text;
  ASSERT_FALSE(ended.statuses.empty());
  EXPECT_EQ(ended.statuses.back(), std::make_pair(std::string("failed"), why));
}

TEST(SdkPlantEnds, AnInfiniteEnergyFromInitialIsRefusedNamingTheField) {
  int brakes = 0;
  sdk::PlantOptions options;
  options.brake = [&] { ++brakes; };
  options.initial = [] {
    sdk::PlantState s{{0.1, 0.2}, {0.0, 0.0}};
    s.potential_energy = std::numeric_limits<double>::infinity();
    return s;
  };
  const Ended ended = serve(options);
  EXPECT_EQ(ended.code, 1);
  EXPECT_EQ(brakes, 1);
  const std::string why =
      "initial() returned inf for potential_energy; expected a finite number [J], or NaN (not known)";
  ASSERT_FALSE(ended.statuses.empty());
  EXPECT_EQ(ended.statuses.back(), std::make_pair(std::string("failed"), why));
}

TEST(SdkPlantEnds, ALimitCrossedBrakesOnceAndDoesNotClaimZeroTorque) {
  int brakes = 0;
  sdk::PlantOptions options;
  options.brake = [&] { ++brakes; };
  options.limits.emplace();
  options.limits->position = std::vector<std::pair<double, double>>{{-1.0, 1.0}, {0.5, 1.0}};
  const Ended ended = serve(options);
  EXPECT_EQ(ended.code, 1);
  EXPECT_EQ(brakes, 1);
  EXPECT_EQ(countOf(ended.stderr_text, "plant: calling brake()"), 1) << ended.stderr_text;
  const std::string why =
      "joint 2's position 0.2 rad is outside its limits [0.5, 1] at tick 0 (t = 0 s); the plant stopped the "
      "run (its limits)";
  ASSERT_FALSE(ended.statuses.empty());
  EXPECT_EQ(ended.statuses.back(), std::make_pair(std::string("failed"), why));
}

TEST(SdkPlantEnds, AStopBySigtermIsInterruptedAndBrakesOnce) {
  int brakes = 0;
  sdk::PlantOptions options;
  options.brake = [&] { ++brakes; };
  options.initial = [] {
    std::raise(SIGTERM);  // the launcher stops the run: noted by runPlant's handler
    return sdk::PlantState{{0.1, 0.2}, {0.0, 0.0}};
  };
  const Ended ended = serve(options);
  EXPECT_EQ(ended.code, 0);
  EXPECT_EQ(brakes, 1);
  EXPECT_EQ(countOf(ended.stderr_text, "plant: calling brake()"), 1) << ended.stderr_text;
  ASSERT_FALSE(ended.statuses.empty());
  EXPECT_EQ(ended.statuses.back().first, "interrupted");
}

TEST(SdkPlantEnds, ABrakeThatThrowsAtAStopFailsTheRunNamingIt) {
  sdk::PlantOptions options;
  options.brake = [] { throw std::runtime_error("the brake relay is open"); };
  options.initial = [] {
    std::raise(SIGINT);
    return sdk::PlantState{{0.1, 0.2}, {0.0, 0.0}};
  };
  const Ended ended = serve(options);
  EXPECT_EQ(ended.code, 1);
  EXPECT_EQ(countOf(ended.stderr_text, "plant: calling brake()"), 1) << ended.stderr_text;
  ASSERT_FALSE(ended.statuses.empty());
  EXPECT_EQ(ended.statuses.back(),
            std::make_pair(std::string("failed"), std::string("brake() failed: the brake relay is open")));
}

TEST(SdkPlantEnds, WithoutABrakeNothingIsCalled) {
  sdk::PlantOptions options;
  options.initial = []() -> sdk::PlantState { throw 42; };
  const Ended ended = serve(options);
  EXPECT_EQ(ended.code, 1);
  EXPECT_EQ(ended.stderr_text.find("brake()"), std::string::npos) << ended.stderr_text;
  ASSERT_FALSE(ended.statuses.empty());
  EXPECT_EQ(ended.statuses.back(),
            std::make_pair(std::string("failed"),
                           std::string("initial() failed: it threw something that is not a std::exception")));
}

}  // namespace
}  // namespace lagrange::testing
