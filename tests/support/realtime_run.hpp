#pragma once
/// @file
/// What a realtime run's test may assert without timing it: how many ticks
/// the controller answers depends on the machine's load (a starved
/// controller skips ticks and the plant holds its torque, which the summary
/// counts), so tests check convergence and the accounting, never a count.

#include <gtest/gtest.h>

#include <string>

#include "support/run_log.hpp"

namespace lagrange::testing {

/// The run met its tracking tolerance, and every command the controller
/// published is in run.lcm or counted missing there (log.missing_records).
inline void expectTheArmTrackedAndEveryCommandIsAccountedFor(const std::string& dir) {
  const auto j = readSummary(dir);
  EXPECT_TRUE(j["tracking"]["met"].get<bool>()) << j["tracking"].dump();
  const long long published = j["messages"]["CONTROL_COMMAND"]["published"].get<long long>();
  const long long missing = j["log"]["missing_records"]["CONTROL_COMMAND"].get<long long>();
  const long long logged = static_cast<long long>(readCommands(dir + "/run.lcm").size());
  EXPECT_GT(published, 0);
  EXPECT_EQ(logged + missing, published) << "logged " << logged << ", counted missing " << missing;
}

}  // namespace lagrange::testing
