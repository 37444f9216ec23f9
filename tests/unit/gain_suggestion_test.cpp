// check-gains --suggest: the constructive rules produce gains that pass.
#include "controller/gain_suggestion.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "controller/gain_report.hpp"
#include "controller/paper_section.hpp"
#include "support/configs.hpp"

namespace lagrange::controller {
namespace {

using testing::kConfigs;

TEST(GainSuggestion, RepairsAViolatedEquation11) {
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_2dof.yaml", {"controller.kd=0.01"});
  ASSERT_FALSE(checkGains(s).holds());
  const config::Scenario fixed = suggestGains(s);
  EXPECT_TRUE(checkGains(fixed).holds());
  EXPECT_EQ(controller::paperSettings(fixed).gains.kp,
            controller::paperSettings(s).gains.kp);  // only what the condition needs changes
}

TEST(GainSuggestion, MeetsTheorem2ForOneIntegrator) {
  const config::Scenario s = config::loadScenario(kConfigs + "/chain_m1.yaml");
  ASSERT_FALSE(checkGains(s).holds());
  const GainReport r = checkGains(suggestGains(s));
  ASSERT_EQ(r.chain.size(), 3u);
  for (const auto& c : r.chain) EXPECT_TRUE(c.holds) << c.name << ": " << c.lhs << " > " << c.rhs;
  // (794a): kp1 = kd1.
  const config::Scenario g = suggestGains(s);
  EXPECT_EQ(controller::paperSettings(g).stages[0].kp, controller::paperSettings(g).stages[0].kd);
  EXPECT_NE(controllerYaml(g).find("stages:"), std::string::npos);
}

// m >= 2: Proposition 1's rules, with (795a) read with kd_i^2 and the later
// stages strengthened, meet Theorem 3 and every condition of the proposition,
// although the gains reach 1e30 and beyond (the checks scale their matrices).
config::Scenario withOrder(int m) {
  config::Scenario s = config::loadScenario(kConfigs + "/chain_m3.yaml");
  s.actuator.order = m;
  controller::paperSettings(s).stages.resize(m, controller::paperSettings(s).stages.back());
  return s;
}

TEST(GainSuggestion, MeetsTheorem3AndProposition1ForTwoAndThreeIntegrators) {
  for (int m = 2; m <= 3; ++m) {
    const config::Scenario s = withOrder(m);
    const GainReport before = checkGains(s);
    EXPECT_FALSE(before.holds());
    EXPECT_FALSE(before.propositionHolds());
    const config::Scenario g = suggestGains(s);
    ASSERT_EQ(controller::paperSettings(g).stages.size(), static_cast<size_t>(m));
    const GainReport r = checkGains(g);
    ASSERT_EQ(r.chain.size(), 3u);
    for (const auto& c : r.chain)
      EXPECT_TRUE(c.holds) << "m = " << m << ", " << c.name << ": " << c.lhs << " > " << c.rhs;
    ASSERT_EQ(r.proposition.size(), 9u);  // (632a-c), (794a-b), (795a-c), the matrix
    for (const auto& c : r.proposition)
      EXPECT_TRUE(c.holds) << "m = " << m << ", " << c.name << ": " << c.lhs << " > " << c.rhs;
    EXPECT_GT(controller::paperSettings(g).stages.back().kp(0), 1e30);
  }
}

TEST(GainSuggestion, SaysWhenTheConstructiveGainsOverflowDouble) {
  // m = 4: stage 4's kp would be ~(1e11 * 1e12^2 * 1e41^2 * 1e125^2), beyond 1.8e308.
  try {
    suggestGains(withOrder(4));
    FAIL() << "expected std::range_error";
  } catch (const std::range_error& e) {
    EXPECT_NE(std::string(e.what()).find("overflow double precision at stage 4"), std::string::npos)
        << e.what();
  }
}

// The search (#52): at a rate where no gains keeping eq. (12) are stable it
// suggests nothing and names both binding conditions with their numbers; where
// some are, it suggests gains that hold eq. (12) and are stable at the rate.
TEST(GainSearch, SuggestsNothingWhereEq11AndTheRateCannotBothHold) {
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_5link.yaml", {"plant.publish_rate=200"});
  const GainSearch search = searchGains(s);
  EXPECT_FALSE(search.suggested);
  EXPECT_NE(search.binding.find("eq. (12) against the rate"), std::string::npos) << search.binding;
  ASSERT_TRUE(search.sufficient_rate) << search.binding;
  EXPECT_GT(*search.sufficient_rate, 200.0);
  ASSERT_TRUE(search.kdelta_allowed) << search.binding;
  EXPECT_LT(*search.kdelta_allowed, search.kdelta);
}

TEST(GainSearch, SuggestsGainsThatHoldEq11AndAreStableAtTheRate) {
  const config::Scenario s =
      config::loadScenario(kConfigs + "/rigid_5link.yaml", {"controller.kd=[4, 4, 4, 4, 4]"});
  ASSERT_FALSE(checkGains(s, false).holds());
  const GainSearch search = searchGains(s);
  ASSERT_TRUE(search.suggested) << search.binding;
  const GainReport r = checkGains(*search.suggested);
  EXPECT_TRUE(r.holds());
  EXPECT_TRUE(r.sampled.verdict == "adequate" || r.sampled.verdict == "slow") << describe(r.sampled);
}

}  // namespace
}  // namespace lagrange::controller
