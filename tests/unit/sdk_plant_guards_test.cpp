// The C++ SDK's plant guards (sdk/external_plant.cpp), the pure pieces of
// lagrange::sdk::runPlant: the realtime stale-torque rule with its watchdog
// (TorqueChoice, the Python module's and the built-in plant's rule), and the
// limits a bridge enforces (PlantLimits: clipping, breaches, their checks).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lagrange/sdk/external_plant.hpp"

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

}  // namespace
}  // namespace lagrange::testing
