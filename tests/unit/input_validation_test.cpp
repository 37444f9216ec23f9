// What a process's node refuses as invalid, deterministically: signed,
// intact, this run's, yet malformed messages -- a position of the wrong
// size or with NaN, an actuator state of the wrong chain order, size or
// torque steps -- each counted as invalid with its reason, never handed to
// the mathematics. (The runs under such traffic, bad_input_test.cpp, race
// the real publisher: once it has spoken, the injector's messages are
// refused earlier, as replays of a replaced process.)
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "controller/controller_lcm.hpp"
#include "controller/input_assembly.hpp"
#include "support/bad_actuator_states.hpp"
#include "transport/channels.hpp"
#include "transport/checksum.hpp"
#include "transport/lcm_node.hpp"
#include "transport/message_auth.hpp"
#include "transport/messages.hpp"

namespace lagrange::transport {
namespace {

constexpr int64_t kRun = 42;

MessageKey key() {
  MessageKey k{};
  k.fill(3);
  return k;
}

// As `publisher` of this run would send it, signed; then handled.
template <class Msg>
void sendAs(LcmNode& node, const std::string& channel, Msg m, const std::string& publisher, int64_t seq) {
  m.header.run_id = kRun;
  m.header.publisher = publisher;
  m.header.publisher_pid = 9;
  m.header.seq = seq;
  seal(m);
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  MessageAuthenticator(key()).sign(bytes);
  node.raw().publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
  while (node.drain() > 0) {
  }
}

long long invalid(const LcmNode& node, const std::string& channel) {
  return node.counters().at(channel).rejected_by[static_cast<size_t>(RejectReason::kInvalid)];
}

TEST(InputValidation, PositionsOfTheWrongSizeOrWithNanAreRefusedAsInvalidWithTheirReason) {
  LcmNode node("controller", "memq://", kRun);
  node.authenticate(key());
  int handled = 0;
  node.subscribe<lagrange::plant_position_t>(
      kPlantPosition, [](const lagrange::plant_position_t& m) { return validate(m, 2); },
      [&](const lagrange::plant_position_t&) { ++handled; });
  lagrange::plant_position_t wrong_size;
  wrong_size.header = makeHeader(5, 0.005);
  wrong_size.num_joints = 3;
  wrong_size.q = {1, 2, 3};
  sendAs(node, kPlantPosition, wrong_size, "plant", 1);
  EXPECT_NE(node.lastInvalid().find("num_joints is 3, expected 2"), std::string::npos) << node.lastInvalid();
  lagrange::plant_position_t nan = wrong_size;
  nan.num_joints = 2;
  nan.q = {std::nan(""), 0.0};
  sendAs(node, kPlantPosition, nan, "plant", 2);
  EXPECT_NE(node.lastInvalid().find("non-finite"), std::string::npos) << node.lastInvalid();
  EXPECT_NE(node.lastInvalid().find("(from 'plant', tick 5)"), std::string::npos) << node.lastInvalid();
  // Finite, but past any arm's range: the plant's number, refused as the
  // plant's, before a controller turns it into an infinite torque.
  lagrange::plant_position_t huge = nan;
  huge.q = {0.0, 1e308};
  sendAs(node, kPlantPosition, huge, "plant", 3);
  EXPECT_NE(node.lastInvalid().find("value 1e+308 of joint 2 is past any arm's range"), std::string::npos)
      << node.lastInvalid();
  EXPECT_EQ(invalid(node, kPlantPosition), 3);
  EXPECT_EQ(handled, 0);
  lagrange::plant_position_t good = nan;
  good.q = {0.1, -1e9};  // at the bound: still an arm's
  sendAs(node, kPlantPosition, good, "plant", 4);
  EXPECT_EQ(handled, 1);
}

TEST(InputValidation, ActuatorStatesOfTheWrongOrderSizeOrStepsAreRefusedByTheCascadedControllersInputs) {
  LcmNode node("controller", "memq://", kRun);
  node.authenticate(key());
  controller::Needs needs;
  needs.actuator_order = 1;
  controller::InputAssembly assembly(needs, Eigen::MatrixXd::Zero(1, 2), Eigen::MatrixXd());
  controller::subscribeDeclaredInputs(node, needs, {2, 1, false}, assembly);
  const auto [wrong_order, wrong_size, wrong_steps] = testing::badActuatorStates(7, 0.007);
  sendAs(node, kActuatorState, wrong_order, "actuator", 1);
  EXPECT_NE(node.lastInvalid().find("actuator order is 2, expected 1"), std::string::npos)
      << node.lastInvalid();
  sendAs(node, kActuatorState, wrong_size, "actuator", 2);
  EXPECT_NE(node.lastInvalid().find("num_joints is 3, expected 2"), std::string::npos) << node.lastInvalid();
  sendAs(node, kActuatorState, wrong_steps, "actuator", 3);
  EXPECT_NE(node.lastInvalid().find("torque_steps is 2, expected 1"), std::string::npos)
      << node.lastInvalid();
  EXPECT_EQ(invalid(node, kActuatorState), 3);
}

// The run's clock is the scenario's: a tick of the run, and that tick's time
// (to a millionth of a period), whatever a participant stamps.
TEST(ValidateClock, RefusesTicksOutsideTheRunAndATimeThatIsNotTheTicks) {
  const double period = 1.0 / 1000.0;
  lagrange::header_t h{};
  h.tick = 200;
  h.sim_time = 200 * period;
  EXPECT_EQ(validateClock(h, 200, period), "");
  h.sim_time = 0.2;  // 200 / 1000: not bit-equal to 200 x (1 / 1000), within the tolerance
  EXPECT_EQ(validateClock(h, 200, period), "");
  h.tick = 201;
  h.sim_time = 201 * period;
  EXPECT_EQ(validateClock(h, 200, period), "tick 201 is outside the run (its ticks are 0 to 200)");
  h.tick = -1;
  EXPECT_NE(validateClock(h, 200, period).find("outside the run"), std::string::npos);
  h.tick = 100;
  h.sim_time = 0.05;  // half its tick's time: a plant making a late run look quick
  const std::string why = validateClock(h, 200, period);
  EXPECT_NE(why.find("sim_time 0.050000 s is not its tick's time (tick 100"), std::string::npos) << why;
  h.sim_time = std::nan("");
  EXPECT_NE(validateClock(h, 200, period), "");
}

}  // namespace
}  // namespace lagrange::transport
