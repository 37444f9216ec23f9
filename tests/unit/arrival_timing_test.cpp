// logger::ArrivalTiming: a loop judged by its messages' arrivals -- jitter
// as the intervals' distance from the period, each period that passed
// without a message a miss, copies of a tick counted once.
#include "logger/arrival_timing.hpp"

#include <gtest/gtest.h>

namespace lagrange::logger {
namespace {

TEST(ArrivalTiming, JitterMissesAndRateFromTheArrivals) {
  ArrivalTiming timing(0.001);
  double t = 0.0;
  for (int64_t k = 0; k < 100; ++k) {
    t += k == 50 ? 0.0035 : (k % 2 == 0 ? 0.0011 : 0.0009);  // +-0.1 ms, and one gap of 3.5 periods
    timing.arrived(k, t);
    if (k == 20) timing.arrived(k, t + 0.0002);  // a copy: counted once
  }
  const nlohmann::json j = timing.loopJson();
  EXPECT_EQ(j["cycles"], 100);
  EXPECT_EQ(j["deadline_misses"], 3);  // 3.5 periods without a message: 4 rounded, 3 missed
  EXPECT_EQ(j["longest_miss_run"], 3);
  EXPECT_NEAR(j["on_time_fraction"].get<double>(), 100.0 / 103.0, 1e-12);
  EXPECT_NEAR(j["jitter"]["p50"].get<double>(), 1e-4, 2e-6);  // 1 % bins
  EXPECT_NEAR(j["jitter"]["max"].get<double>(), 2.5e-3, 1e-9);
  EXPECT_NEAR(j["achieved_rate"].get<double>(), 99.0 / (t - 0.0011), 1e-6);
  EXPECT_EQ(j["period"], 0.001);
}

TEST(ArrivalTiming, GapsApartAreSeparateRunsOfMisses) {
  ArrivalTiming timing(1.0);
  for (const double t : {0.0, 3.0, 6.0, 7.0, 12.0}) timing.arrived(static_cast<int64_t>(t), t);
  const nlohmann::json j = timing.loopJson();
  EXPECT_EQ(j["deadline_misses"], 2 + 2 + 4);
  EXPECT_EQ(j["longest_miss_run"], 4);  // not 2 + 2: a message came between
}

TEST(ArrivalTiming, FewerThanTwoArrivalsIsNoLoop) {
  ArrivalTiming timing(0.001);
  EXPECT_TRUE(timing.loopJson().is_null());
  timing.arrived(0, 1.0);
  timing.arrived(0, 1.5);
  EXPECT_TRUE(timing.loopJson().is_null());
}

}  // namespace
}  // namespace lagrange::logger
