// OUT/gains.json: the launcher's gain check, read back by the controller and
// the logger exactly as it was computed, and never used for another scenario.
#include "controller/gain_report_json.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "support/configs.hpp"
#include "support/temp_dir.hpp"

namespace lagrange::controller {
namespace {

using testing::kConfigs;

void expectSameCondition(const model::ConditionReport& a, const model::ConditionReport& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.expression, b.expression);
  EXPECT_EQ(a.lhs, b.lhs) << a.name;  // exactly: the logger's summary.json prints them
  EXPECT_EQ(a.rhs, b.rhs) << a.name;
  EXPECT_EQ(a.holds, b.holds) << a.name;
}

void expectSameReport(const GainReport& a, const GainReport& b) {
  EXPECT_EQ(a.kc, b.kc);
  EXPECT_EQ(a.kc_proven, b.kc_proven);
  EXPECT_EQ(a.kc_found, b.kc_found);
  EXPECT_EQ(a.kdelta, b.kdelta);
  EXPECT_EQ(a.kdelta_exact, b.kdelta_exact);
  expectSameCondition(a.condition, b.condition);
  ASSERT_EQ(a.chain.size(), b.chain.size());
  for (size_t i = 0; i < a.chain.size(); ++i) expectSameCondition(a.chain[i], b.chain[i]);
  ASSERT_EQ(a.proposition.size(), b.proposition.size());
  for (size_t i = 0; i < a.proposition.size(); ++i) expectSameCondition(a.proposition[i], b.proposition[i]);
  ASSERT_EQ(a.eta.has_value(), b.eta.has_value());
  if (a.eta) {
    EXPECT_EQ(a.eta->eta1, b.eta->eta1);
    EXPECT_EQ(a.eta->eta2, b.eta->eta2);
    EXPECT_EQ(a.eta->eta3, b.eta->eta3);
  }
  EXPECT_EQ(a.warnings, b.warnings);
  EXPECT_EQ(a.sampled.rate, b.sampled.rate);
  EXPECT_EQ(a.sampled.spectral_radius, b.sampled.spectral_radius);
  EXPECT_EQ(a.sampled.worst_time, b.sampled.worst_time);
  EXPECT_EQ(a.sampled.sampled_decay, b.sampled.sampled_decay);
  EXPECT_EQ(a.sampled.continuous_decay, b.sampled.continuous_decay);
  EXPECT_EQ(a.sampled.fastest_mode, b.sampled.fastest_mode);
  EXPECT_EQ(a.sampled.verdict, b.sampled.verdict);
  EXPECT_EQ(a.sampled.why, b.sampled.why);
  EXPECT_EQ(a.sampled.sufficient_rate, b.sampled.sufficient_rate);
  EXPECT_EQ(a.sampled.one_period_delay, b.sampled.one_period_delay);
  EXPECT_EQ(a.unchecked, b.unchecked);
  ASSERT_EQ(a.simulated.has_value(), b.simulated.has_value());
  if (a.simulated) {
    EXPECT_EQ(a.simulated->fine_rate, b.simulated->fine_rate);
    EXPECT_EQ(a.simulated->confirmed_at, b.simulated->confirmed_at);
    EXPECT_EQ(a.simulated->verdict, b.simulated->verdict);
    ASSERT_EQ(a.simulated->starts.size(), b.simulated->starts.size());
    for (size_t i = 0; i < a.simulated->starts.size(); ++i) {
      EXPECT_EQ(a.simulated->starts[i].sampled_time, b.simulated->starts[i].sampled_time);
      EXPECT_EQ(a.simulated->starts[i].fine_error, b.simulated->starts[i].fine_error);
    }
  }
  EXPECT_EQ(describe(a), describe(b));
}

class GainsFile : public testing::TempDirTest {
 protected:
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }
};

// Theorem 1 on the planar arm (k_c proven), and the cascaded controller with
// m = 3 (Theorem 3's conditions, Proposition 1, eta, a warning, a sampled-data
// verdict with a sufficient rate): every field comes back bit for bit.
// A simulated sampled-data verdict (wiring::simulateSampledData's; made up
// here) comes back too, times and all, and its absence stays absent.
TEST(GainReportJson, GivesBackTheSimulatedVerdict) {
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_2dof.yaml");
  GainReport r = checkGains(s, false);
  SampledSimulation sim;
  sim.rate = 1000;
  sim.fine_rate = 8000;
  sim.confirmed_at = 16000;
  sim.duration = 10;
  sim.tolerance = 1e-3;
  sim.starts = {{"the initial state", "completed", "completed", 0.915, 0.896, 1.24e-5, 1.28e-6, "adequate"},
                {"seeded state 1", "diverged", "completed", std::nullopt, 0.81, 3.5, 1e-6, "diverges"}};
  sim.verdict = "diverges";
  sim.why = "the sampled loop diverged from seeded state 1";
  sim.wall_time = 4.2;
  r.simulated = sim;
  const HandedGainReport back = gainReportFromJson(gainReportJson(r, config::toYaml(s)), config::toYaml(s));
  ASSERT_TRUE(back.report) << back.why_not;
  expectSameReport(r, *back.report);
  EXPECT_NE(describe(*back.report)
                .find("sampled-data check at 1000 Hz: DIVERGES: the sampled loop diverged from "
                      "seeded state 1\n  from the initial state: the sampled loop converged at "
                      "0.915 s, the fine-rate loop converged at 0.896 s"),
            std::string::npos)
      << describe(*back.report);
  r.simulated.reset();
  const HandedGainReport none = gainReportFromJson(gainReportJson(r, config::toYaml(s)), config::toYaml(s));
  ASSERT_TRUE(none.report);
  EXPECT_FALSE(none.report->simulated.has_value());
}

TEST(GainReportJson, GivesBackEveryFieldExactly) {
  for (const char* name : {"rigid_2dof", "chain_m3"}) {
    SCOPED_TRACE(name);
    const config::Scenario s = config::loadScenario(kConfigs + "/" + name + ".yaml");
    const GainReport r = checkGains(s);
    const HandedGainReport back = gainReportFromJson(gainReportJson(r, config::toYaml(s)), config::toYaml(s));
    ASSERT_TRUE(back.report) << back.why_not;
    expectSameReport(r, *back.report);
  }
  // The cascaded report does fill what the comparison covers.
  const GainReport cascaded = checkGains(config::loadScenario(kConfigs + "/chain_m3.yaml"));
  EXPECT_TRUE(cascaded.eta.has_value());
  EXPECT_FALSE(cascaded.proposition.empty());
  EXPECT_FALSE(cascaded.sampled.verdict.empty());
}

TEST(GainReportJson, KeepsInfinitiesAndNan) {
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_2dof.yaml");
  GainReport r = checkGains(s, false);
  r.condition.lhs = std::numeric_limits<double>::infinity();
  r.condition.rhs = -std::numeric_limits<double>::infinity();
  r.kc = std::numeric_limits<double>::quiet_NaN();
  r.sampled.sufficient_rate = 1e300;
  const HandedGainReport back = gainReportFromJson(gainReportJson(r, config::toYaml(s)), config::toYaml(s));
  ASSERT_TRUE(back.report) << back.why_not;
  EXPECT_EQ(back.report->condition.lhs, std::numeric_limits<double>::infinity());
  EXPECT_EQ(back.report->condition.rhs, -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(back.report->kc));
  EXPECT_EQ(back.report->sampled.sufficient_rate, 1e300);
}

TEST(GainReportJson, IsNotUsedForAnotherScenario) {
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_2dof.yaml");
  const config::Scenario other =
      config::loadScenario(kConfigs + "/rigid_2dof.yaml", {"controller.kd=[30,30]"});
  const HandedGainReport back =
      gainReportFromJson(gainReportJson(checkGains(s, false), config::toYaml(s)), config::toYaml(other));
  EXPECT_FALSE(back.report);
  EXPECT_NE(back.why_not.find("another scenario"), std::string::npos) << back.why_not;
}

// The process takes the launcher's report as it is: a planted k_c comes back
// (nothing was recomputed), without the sampled-data check the processes
// leave to the launcher.
TEST_F(GainsFile, AProcessReadsTheLaunchersReport) {
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_2dof.yaml");
  GainReport planted = checkGains(s);
  ASSERT_FALSE(planted.sampled.verdict.empty());
  planted.kc = 12345.678;
  const ProcessGainReport got =
      processGainReport(s, write("gains.json", gainReportJson(planted, config::toYaml(s))));
  EXPECT_EQ(got.note, "");
  EXPECT_EQ(got.report.kc, 12345.678);
  EXPECT_EQ(got.report.sampled.verdict, "");  // apart, for the logger alone
  ASSERT_TRUE(got.sampled);
  EXPECT_EQ(got.sampled->spectral_radius, planted.sampled.spectral_radius);
  EXPECT_EQ(got.report.condition.lhs, planted.condition.lhs);
}

// A file it cannot use costs time, never a wrong report: the process checks
// the gains itself, and says why.
TEST_F(GainsFile, AProcessChecksItselfWhenTheFileCannotBeUsed) {
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_2dof.yaml");
  const config::Scenario other =
      config::loadScenario(kConfigs + "/rigid_2dof.yaml", {"controller.kd=[30,30]"});
  GainReport wrong = checkGains(other, false);
  wrong.kc = 12345.678;
  std::string v2 = gainReportJson(wrong, config::toYaml(s));
  v2.replace(v2.find("\"format\": 1"), 11, "\"format\": 2");
  const GainReport expected = checkGains(s, false);
  const struct {
    std::string path, said;
  } cases[] = {
      {dir_ + "/absent.json", "absent.json"},
      {dir_, "is a directory"},
      {write("garbage.json", "{\"format\": 1, \"report\": [tru"), "not a gain report"},
      {write("other.json", gainReportJson(wrong, config::toYaml(other))), "another scenario"},
      {write("v2.json", v2), "format 2"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.path);
    const ProcessGainReport got = processGainReport(s, c.path);
    EXPECT_NE(got.note.find("--gains " + c.path + " not used"), std::string::npos) << got.note;
    EXPECT_NE(got.note.find(c.said), std::string::npos) << got.note;
    EXPECT_FALSE(got.sampled);
    expectSameReport(got.report, expected);
  }
  // No file named: the check, silently (a process started by hand).
  const ProcessGainReport plain = processGainReport(s, "");
  EXPECT_EQ(plain.note, "");
  expectSameReport(plain.report, expected);
}

}  // namespace
}  // namespace lagrange::controller
