// logger::AnswerTimes: each answer timed from its question's first copy,
// copies and answers to nothing ignored, a wait past the threshold said
// once while it lasts (then at most every repeat interval), the median (to
// 1 %) and the worst (exact) in the summary.
#include "logger/answer_times.hpp"

#include <gtest/gtest.h>

namespace lagrange::logger {
namespace {

AnswerTimes controllerOnly(double threshold) {
  return AnswerTimes({{"controller", "python3 pd.py", "PLANT_POSITION", "CONTROL_COMMAND"}}, threshold);
}

TEST(AnswerTimes, TimesEachAnswerFromTheFirstCopyOfItsQuestion) {
  AnswerTimes a = controllerOnly(1.0);
  a.arrived("PLANT_POSITION", 0, 10.0);
  a.arrived("PLANT_POSITION", 0, 10.5);  // re-sent: the wait began at 10.0
  a.arrived("CONTROL_COMMAND", 0, 10.25);
  a.arrived("CONTROL_COMMAND", 0, 10.9);  // a copy of the answer
  a.arrived("PLANT_POSITION", 0, 11.0);   // re-sent after the answer: no new wait
  a.arrived("CONTROL_COMMAND", 7, 11.0);  // an answer to nothing heard
  a.arrived("PLANT_POSITION", 1, 12.0);
  a.arrived("CONTROL_COMMAND", 1, 14.0);
  a.arrived("PLANT_POSITION", 2, 15.0);
  a.arrived("CONTROL_COMMAND", 2, 15.5);
  const nlohmann::json j = a.summary();
  EXPECT_EQ(j["threshold"], 1.0);
  const nlohmann::json& c = j["controller"];
  EXPECT_EQ(c["program"], "python3 pd.py");
  EXPECT_EQ(c["answered"], 3);
  EXPECT_NEAR(c["median"].get<double>(), 0.5, 0.0051);  // 1 %-wide bins
  EXPECT_DOUBLE_EQ(c["worst"].get<double>(), 2.0);
  EXPECT_EQ(c["worst_tick"], 1);
  EXPECT_EQ(c["slow"], 1);
}

TEST(AnswerTimes, TheMedianIsWithinOnePercentAboveTheExactOneAndTheWorstExact) {
  AnswerTimes a = controllerOnly(1.0);
  const double took[] = {0.4, 0.1, 0.3, 0.2, 0.5};
  for (int k = 0; k < 5; ++k) {
    a.arrived("PLANT_POSITION", k, k);
    a.arrived("CONTROL_COMMAND", k, k + took[k]);
  }
  const double median = a.summary()["controller"]["median"].get<double>();
  EXPECT_GE(median, 0.3 * (1 - 1e-12));
  EXPECT_LE(median, 0.3 * 1.0101);
  EXPECT_NEAR(a.summary()["controller"]["worst"].get<double>(), 0.5, 1e-12);
  EXPECT_EQ(a.summary()["controller"]["worst_tick"], 4);
}

TEST(AnswerTimes, AWaitPastTheThresholdIsSaidOnceWhileItLastsThenAtMostEveryInterval) {
  AnswerTimes a = controllerOnly(1.0);
  a.arrived("PLANT_POSITION", 5, 100.0);
  EXPECT_TRUE(a.newlySlow(100.9).empty());
  const auto first = a.newlySlow(101.2);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].name, "controller");
  EXPECT_EQ(first[0].tick, 5);
  EXPECT_NEAR(first[0].waited, 1.2, 1e-9);
  EXPECT_TRUE(a.newlySlow(101.4).empty());  // the same wait is said once
  a.arrived("CONTROL_COMMAND", 5, 101.5);
  a.arrived("PLANT_POSITION", 6, 101.5);
  EXPECT_TRUE(a.newlySlow(103.0).empty());  // slow again, but within 10 s of the last line
  const auto again = a.newlySlow(111.3);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].tick, 6);
  EXPECT_EQ(a.summary()["controller"]["slow"], 1);  // the answered one; tick 6 still waits
}

TEST(AnswerTimes, QuestionsPassedByANewerAnswerAreNotWaits) {
  // Realtime: the controller answers the newest position it has.
  AnswerTimes a = controllerOnly(0.5);
  for (int k = 0; k < 10; ++k) a.arrived("PLANT_POSITION", k, 0.001 * k);
  a.arrived("CONTROL_COMMAND", 9, 0.0095);
  EXPECT_TRUE(a.newlySlow(100.0).empty());
  EXPECT_EQ(a.summary()["controller"]["answered"], 1);
  a.arrived("PLANT_POSITION", 3, 0.02);  // older than the answer: never a wait
  EXPECT_TRUE(a.newlySlow(200.0).empty());
}

TEST(AnswerTimes, StrayTicksDoNotGrowItWithoutBound) {
  AnswerTimes a = controllerOnly(1.0);
  for (int64_t k = 0; k < 100000; ++k) a.arrived("PLANT_POSITION", 1000000 + k, 0.0);
  a.arrived("CONTROL_COMMAND", 1000000, 0.5);  // dropped as the oldest: nothing to answer
  EXPECT_EQ(a.summary()["controller"]["answered"], 0);
  a.arrived("CONTROL_COMMAND", 1099999, 0.5);
  EXPECT_EQ(a.summary()["controller"]["answered"], 1);
}

TEST(AnswerTimes, NoAnswerGivesNullTimes) {
  const nlohmann::json c = controllerOnly(1.0).summary()["controller"];
  EXPECT_EQ(c["answered"], 0);
  EXPECT_TRUE(c["median"].is_null());
  EXPECT_TRUE(c["worst"].is_null());
  EXPECT_TRUE(c["worst_tick"].is_null());
}

}  // namespace
}  // namespace lagrange::logger

namespace lagrange::logger {
namespace {

// The plant answers the actuator's state of tick k with its position of
// tick k + 1: a plant that takes seconds a step is timed, said while it
// lasts, and counted as a slow controller is.
TEST(AnswerTimes, ThePlantAnswersEachTorqueWithItsNextTick) {
  AnswerTimes a({{"plant", "python3 arm.py", "ACTUATOR_STATE", "PLANT_POSITION", 1}}, 1.0);
  a.arrived("PLANT_POSITION", 0, 0.0);  // the first position answers nothing
  a.arrived("ACTUATOR_STATE", 0, 0.1);
  a.arrived("PLANT_POSITION", 1, 0.3);  // 0.2 s
  a.arrived("ACTUATOR_STATE", 1, 0.4);
  EXPECT_TRUE(a.newlySlow(1.0).empty()) << "0.6 s is within the threshold";
  const std::vector<AnswerTimes::Slow> slow = a.newlySlow(15.4);
  ASSERT_EQ(slow.size(), 1u);
  EXPECT_EQ(slow[0].name, "plant");
  EXPECT_EQ(slow[0].tick, 1);
  EXPECT_NEAR(slow[0].waited, 15.0, 1e-9);
  a.arrived("PLANT_POSITION", 2, 15.4);  // tick 1's torque answered after 15 s
  const nlohmann::json j = a.summary()["plant"];
  EXPECT_EQ(j["answered"], 2);
  EXPECT_NEAR(j["worst"].get<double>(), 15.0, 1e-9);
  EXPECT_EQ(j["worst_tick"], 1);
  EXPECT_EQ(j["slow"], 1);
}

}  // namespace
}  // namespace lagrange::logger
