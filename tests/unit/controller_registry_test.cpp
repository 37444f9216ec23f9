// The controller seam's contract for the paper's controllers: what each
// declares it needs, that reset() returns it to its configured start, and
// that the registry refuses what it does not know.
#include <gtest/gtest.h>

#include <stdexcept>

#include "config/scenario.hpp"
#include "controller/registry.hpp"

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

}  // namespace
}  // namespace lagrange::controller
