// The gain conditions are named by the numbers the paper prints, with the
// LaTeX source's label as a secondary key (#54 item 5): a reader finds
// "eq. (12)" in the paper, where the source says \label{11}.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "model/gain_conditions.hpp"
#include "support/configs.hpp"

namespace lagrange {
namespace {

using testing::kConfigs;

std::vector<model::ConditionReport> allConditions(const controller::GainReport& r) {
  std::vector<model::ConditionReport> all{r.condition};
  all.insert(all.end(), r.chain.begin(), r.chain.end());
  all.insert(all.end(), r.proposition.begin(), r.proposition.end());
  return all;
}

TEST(PaperNumbers, ConditionsAreNamedAsPrintedWithTheirLabels) {
  // Printed number -> label, read off LaTeX's own .aux for the paper (docs/citing.md).
  const std::map<std::string, std::string> printed_label{
      {"eq. (12)", "11"},    {"eq. (56a)", "632a"}, {"eq. (56b)", "632b"}, {"eq. (56c)", "632c"},
      {"eq. (74)", "lego"},  {"eq. (75)", "786"},   {"eq. (79a)", "794a"}, {"eq. (79b)", "794b"},
      {"eq. (80a)", "795a"}, {"eq. (80b)", "795b"}, {"eq. (80c)", "795c"}};
  const std::set<std::string> unnumbered{"A Hurwitz (Theorem 6)", "Q - diag(Q)/2 >= 0 (Proposition 1)"};
  std::set<std::string> seen;
  for (const char* name : {"rigid_2dof", "chain_m1", "chain_m3"}) {
    SCOPED_TRACE(name);
    const auto report = controller::checkGains(config::loadScenario(kConfigs + "/" + name + ".yaml"), false);
    for (const auto& c : allConditions(report)) {
      seen.insert(c.name);
      const auto known = printed_label.find(c.name);
      if (known != printed_label.end()) {
        EXPECT_EQ(model::paperLabel(c.name), known->second) << c.name;
      } else {
        EXPECT_TRUE(unnumbered.count(c.name))
            << "a condition named neither as printed nor unnumbered: " << c.name;
        EXPECT_EQ(model::paperLabel(c.name), "") << c.name;
      }
    }
  }
  // The three configs reach Theorem 4's, Theorem 5's (m = 1) and Theorem 6's conditions.
  for (const char* name :
       {"eq. (12)", "eq. (56a)", "eq. (74)", "eq. (75)", "eq. (80c)", "A Hurwitz (Theorem 6)"})
    EXPECT_TRUE(seen.count(name)) << name;
  // What a reader is told of is the failing condition: chain_m2's eq. (12)
  // holds, its Theorem 6 conditions do not.
  const auto chain = controller::checkGains(config::loadScenario(kConfigs + "/chain_m2.yaml"), false);
  ASSERT_TRUE(chain.condition.holds);
  ASSERT_FALSE(chain.holds());
  EXPECT_FALSE(chain.binding().holds);
  EXPECT_EQ(chain.binding().margin(), chain.margin());
  EXPECT_NE(chain.binding().name, "eq. (12)");
  const auto rigid = controller::checkGains(config::loadScenario(kConfigs + "/rigid_2dof.yaml"), false);
  EXPECT_EQ(rigid.binding().name, "eq. (12)");
  // A LaTeX label is never a condition's name any more.
  for (const char* old : {"eq. (11)", "eq. (632a)", "eq. (lego)", "eq. (786)"})
    EXPECT_FALSE(seen.count(old)) << old;
}

}  // namespace
}  // namespace lagrange
