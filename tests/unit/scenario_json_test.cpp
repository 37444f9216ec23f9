// The resolved scenario as JSON (config/scenario_json.hpp): the same tree as
// config.resolved.yaml, each scalar typed as YAML's core schema reads it.
#include "config/scenario_json.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/configs.hpp"

namespace lagrange::config {
namespace {

TEST(ScenarioJson, ScalarsAreTypedAsYamlReadsThemAndQuotedOnesStayStrings) {
  const auto j = nlohmann::json::parse(yamlToJson(
      "a: 1.0e-4\nb: 42\nc: true\nd: ~\ne: ode\nf: '12'\ng: [1, -2.5, \"x\"]\nh: nan\ni: .inf\nk: 0x1F\n"));
  EXPECT_EQ(j["a"], 1e-4);
  EXPECT_EQ(j["b"], 42);
  EXPECT_EQ(j["c"], true);
  EXPECT_TRUE(j["d"].is_null());
  EXPECT_EQ(j["e"], "ode");
  EXPECT_EQ(j["f"], "12");  // quoted: a string, whatever it reads like
  EXPECT_EQ(j["g"], nlohmann::json::array({1, -2.5, "x"}));
  // JSON has no NaN, infinity or hexadecimal: those stay as written.
  EXPECT_EQ(j["h"], "nan");
  EXPECT_EQ(j["i"], ".inf");
  EXPECT_EQ(j["k"], "0x1F");
  EXPECT_THROW(yamlToJson("a: [1, 2"), ConfigError);
  // A byte that is not UTF-8 (a URDF's Latin-1 comment) never fails a run.
  EXPECT_EQ(nlohmann::json::parse(yamlToJson("u: \"caf\xe9\"\n"))["u"], "caf\xef\xbf\xbd");
}

TEST(ScenarioJson, EveryShippedScenarioKeepsItsNumbersToTheLastBit) {
  for (const std::string name : {"rigid_2dof", "panda_theorem1", "chain_m2"}) {
    const Scenario s = loadScenario(testing::kConfigs + "/" + name + ".yaml");
    const auto j = nlohmann::json::parse(toJson(s));
    EXPECT_EQ(j["duration"].get<double>(), s.duration) << name;
    EXPECT_EQ(j["plant"]["physics_step"].get<double>(), s.plant.physics_step) << name;
    EXPECT_EQ(j["controller"]["type"], s.controller.type) << name;
    // A vector key holds one number per joint, or one for all (as written).
    const auto& offset = j["reference"]["offset"];
    ASSERT_TRUE(offset.is_number() || offset.size() == static_cast<size_t>(s.dof())) << name << offset;
    for (int i = 0; i < s.dof(); ++i)
      EXPECT_EQ((offset.is_number() ? offset : offset[i]).get<double>(), s.reference.offset(i)) << name;
  }
}

// An external controller's arguments "20" and a scenario named 2026 are
// strings: the emitter writes them unquoted, YAML would read numbers.
TEST(ScenarioJson, TheScenariosStringsStayStringsThoughTheyReadAsNumbers) {
  const Scenario s =
      loadScenario(testing::kConfigs + "/rigid_2dof.yaml",
                   {"name=\"2026\"", "controller={type: external, command: [sh, -c, \"20\", \"1e3\"]}"});
  const auto j = nlohmann::json::parse(toJson(s));
  EXPECT_EQ(j["name"], "2026");
  EXPECT_EQ(j["controller"]["command"], nlohmann::json::array({"sh", "-c", "20", "1e3"}));
}

}  // namespace
}  // namespace lagrange::config
