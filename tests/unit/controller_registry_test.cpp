// The controller seam's contract for the paper's controllers: what each
// declares it needs, that reset() returns it to its configured start, and
// that the registry refuses what it does not know. And the seam config
// knows controllers through: a test-only type with a section of its own.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "config/key_table.hpp"
#include "config/scenario.hpp"
#include "config/yaml_reader.hpp"
#include "controller/paper_section.hpp"
#include "controller/registry.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::controller {
namespace {

config::Scenario shipped(const std::string& name) {
  return config::loadScenario(std::string(LAGRANGE_SOURCE_DIR) + "/configs/" + name + ".yaml", {});
}

// Inputs of a few samples away from the reference, with whatever the controller needs.
std::vector<ControllerInputs> samples(const config::Scenario& s, const Needs& needs) {
  std::vector<ControllerInputs> out;
  for (int k = 0; k < 5; ++k) {
    ControllerInputs in;
    in.t = 1e-3 * k;
    in.q = s.initial_state.q + Eigen::VectorXd::Constant(s.dof(), 0.01 * k);
    if (needs.actuator_order > 0)
      in.xi = s.actuator.initial_state + Eigen::MatrixXd::Constant(needs.actuator_order, s.dof(), 0.1 * k);
    if (needs.motor_angles)
      in.motor_q = s.initial_state.motor_q + Eigen::VectorXd::Constant(s.dof(), 0.02 * k);
    if (needs.motor_rates) in.motor_qdot = Eigen::VectorXd::Constant(s.dof(), 0.5 * k);
    out.push_back(in);
  }
  return out;
}

struct Case {
  const char* config;
  Needs needs;
};

class PaperController : public ::testing::TestWithParam<Case> {};

TEST_P(PaperController, DeclaresWhatItMeasuresAndResetsToItsStart) {
  const config::Scenario s = shipped(GetParam().config);
  const std::unique_ptr<Controller> ctl = makeController(s);
  const Needs needs = ctl->needs();
  EXPECT_EQ(needs.actuator_order, GetParam().needs.actuator_order);
  EXPECT_EQ(needs.motor_angles, GetParam().needs.motor_angles);
  EXPECT_EQ(needs.motor_rates, GetParam().needs.motor_rates);

  const auto inputs = samples(s, needs);
  std::vector<Eigen::VectorXd> first;
  for (const auto& in : inputs) first.push_back(ctl->step(in).u);
  // Without a reset the controller has moved on: time must increase.
  EXPECT_THROW(ctl->step(inputs.front()), std::invalid_argument);
  ctl->reset();
  for (size_t k = 0; k < inputs.size(); ++k) EXPECT_EQ(ctl->step(inputs[k]).u, first[k]) << "sample " << k;
}

INSTANTIATE_TEST_SUITE_P(Shipped, PaperController,
                         ::testing::Values(Case{"rigid_2dof", {0, false, false}},
                                           Case{"chain_m2", {2, false, false}},
                                           Case{"flexible_2dof", {0, true, true}},
                                           Case{"flexible_2dof_filtered_rate", {0, true, false}}));

TEST(ControllerRegistry, RefusesAnUnknownTypeAndATypeTakenTwice) {
  config::Scenario s = shipped("rigid_2dof");
  s.controller.type = "no_such_controller";
  EXPECT_THROW(makeController(s), std::logic_error);
  EXPECT_THROW(registerControllerKind({"theorem1", {}, {}, {}}), std::logic_error);
}

// A type only this file knows, whose section is its own: a gain and a label
// (a text, which per-joint parameters cannot hold). No core: it is never run.
struct SectionedSettings {
  double gain = 0.0;
  std::string label;
};

ControllerKind sectionedKind() {
  ControllerKind kind;
  kind.type = "test_sectioned";
  kind.make = [](const config::Scenario&) -> std::unique_ptr<Controller> { return nullptr; };
  kind.section.read = [](config::MapReader& ctl, const config::Scenario&) -> std::any {
    SectionedSettings settings{ctl.positive("gain"), ctl.text("label", "none")};
    ctl.finish({"type", "gain", "label"});
    return settings;
  };
  kind.section.write = [](YAML::Emitter& out, const config::Scenario& s) {
    const auto& settings = std::any_cast<const SectionedSettings&>(s.controller.settings);
    out << YAML::Key << "gain" << YAML::Value << settings.gain;
    out << YAML::Key << "label" << YAML::Value << settings.label;
  };
  kind.listing = 1000;                               // after every shipped type
  kind.tunable = {{"gain", false, 0.1, 10.0, 1.0}};  // every kind declares one (lagrange tune)
  return kind;
}
const bool sectioned_registered = registerControllerKind(sectionedKind());

TEST(ControllerSection, ATestOnlyTypeReadsAndWritesItsOwnSection) {
  ASSERT_TRUE(sectioned_registered);
  const config::Scenario s =
      config::parseScenario(testing::readFile(testing::kRigid), "rigid_2dof.yaml",
                            {"controller={type: test_sectioned, gain: 2.5, label: ramp}"});
  const auto& settings = std::any_cast<const SectionedSettings&>(s.controller.settings);
  EXPECT_EQ(settings.gain, 2.5);
  EXPECT_EQ(settings.label, "ramp");
  EXPECT_TRUE(s.controller.params.empty());
  // config.resolved.yaml carries it, and reads back the same.
  const config::Scenario again = config::parseScenario(config::toYaml(s), "resolved", {});
  EXPECT_EQ(std::any_cast<const SectionedSettings&>(again.controller.settings).label, "ramp");
  EXPECT_EQ(config::toYaml(again), config::toYaml(s));
  // Its reader's checks are the config's: a wrong value or key names itself.
  const std::string negative =
      testing::errorOf(testing::readFile(testing::kRigid), {"controller={type: test_sectioned, gain: -1}"});
  EXPECT_NE(negative.find("controller.gain"), std::string::npos) << negative;
  EXPECT_THROW(config::parseScenario(testing::readFile(testing::kRigid), "rigid_2dof.yaml",
                                     {"controller={type: test_sectioned, gain: 1, kp: 3}"}),
               config::ConfigError);
  // Listed where it asked to be: last.
  EXPECT_EQ(config::controllerTypes().back(), "test_sectioned");
  // The paper's own settings are not its: asking for them is a programming error.
  EXPECT_THROW(paperSettings(s), std::logic_error);
}

TEST(ControllerSection, ARegistrationThatCannotHoldIsRefused) {
  ControllerKind half = sectionedKind();
  half.type = "test_half_section";
  half.section.write = nullptr;  // a reader without a writer would lose the section in config.resolved.yaml
  EXPECT_THROW(registerControllerKind(half), std::logic_error);
  // Key rows arrive from static initialisers, before the table is first read; later, they would be missing
  // from the known keys already handed out.
  (void)config::keyTable();
  EXPECT_THROW(config::registerKeyRows("test_late", "a late variant", {}), std::logic_error);
}

}  // namespace
}  // namespace lagrange::controller
