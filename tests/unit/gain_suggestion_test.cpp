// check-gains --suggest: the constructive rules produce gains that pass.
#include "controller/gain_suggestion.hpp"

#include <gtest/gtest.h>

#include "controller/gain_report.hpp"

namespace lagrange::controller {
namespace {

const std::string kConfigs = std::string(LAGRANGE_SOURCE_DIR) + "/configs";

TEST(GainSuggestion, RepairsAViolatedEquation11) {
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_2dof.yaml", {"controller.kd=0.01"});
  ASSERT_FALSE(checkGains(s).holds());
  const config::Scenario fixed = suggestGains(s);
  EXPECT_TRUE(checkGains(fixed).holds());
  EXPECT_EQ(fixed.controller.gains.kp, s.controller.gains.kp);  // only what the condition needs changes
}

TEST(GainSuggestion, MeetsTheorem2ForOneIntegrator) {
  const config::Scenario s = config::loadScenario(kConfigs + "/chain_m1.yaml");
  ASSERT_FALSE(checkGains(s).holds());
  const GainReport r = checkGains(suggestGains(s));
  ASSERT_EQ(r.chain.size(), 3u);
  for (const auto& c : r.chain) EXPECT_TRUE(c.holds) << c.name << ": " << c.lhs << " > " << c.rhs;
  // (794a): kp1 = kd1.
  const config::Scenario g = suggestGains(s);
  EXPECT_EQ(g.controller.stages[0].kp, g.controller.stages[0].kd);
  EXPECT_NE(controllerYaml(g).find("stages:"), std::string::npos);
}

}  // namespace
}  // namespace lagrange::controller
