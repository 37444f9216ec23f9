// The controller process's input rule (controller/input_assembly.hpp), without
// LCM: lockstep answers position k only with the measurements of tick k,
// realtime with the newest, and each command names the ticks it used.
#include "controller/input_assembly.hpp"

#include <gtest/gtest.h>

namespace lagrange::controller {
namespace {

Eigen::MatrixXd chain(double v) { return Eigen::MatrixXd::Constant(2, 3, v); }  // order 2, 3 joints
Eigen::MatrixXd motor(double v, int rows) { return Eigen::MatrixXd::Constant(rows, 3, v); }
const Eigen::VectorXd q = Eigen::Vector3d(0.1, 0.2, 0.3);

TEST(InputAssembly, LockstepWaitsForTheChainStateOfItsTick) {
  InputAssembly assembly({2, false, false}, chain(0.0), Eigen::MatrixXd());
  const auto first = assembly.forTick(0, 0.0, q);
  ASSERT_TRUE(first.has_value());  // tick 0: the configured xi(0)
  EXPECT_EQ(first->inputs.xi, chain(0.0));
  EXPECT_EQ(first->inputs.q, q);
  EXPECT_EQ(first->ticks.actuator, -1);
  EXPECT_FALSE(assembly.forTick(1, 0.001, q).has_value());  // ACTUATOR_STATE 0 not here: silent
  assembly.chainState(1000000, chain(99.0));                // a stray far-future state
  EXPECT_FALSE(assembly.forTick(1, 0.001, q).has_value());  // ... is not used for tick 1
  assembly.chainState(0, chain(1.0));                       // xi at t_1
  const auto second = assembly.forTick(1, 0.001, q);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->inputs.xi, chain(1.0));
  EXPECT_EQ(second->ticks.actuator, 0);
  EXPECT_EQ(second->ticks.motor, -1);
  EXPECT_DOUBLE_EQ(second->inputs.t, 0.001);
  EXPECT_EQ(assembly.forTick(1, 0.001, q)->inputs.xi, chain(1.0));  // a re-sent position: the same
}

TEST(InputAssembly, RealtimeUsesTheNewestAndIgnoresALateOlderOne) {
  InputAssembly assembly({2, false, false}, chain(0.0), Eigen::MatrixXd());
  EXPECT_EQ(assembly.newest(0, 0.0, q)->inputs.xi, chain(0.0));
  EXPECT_EQ(assembly.newest(0, 0.0, q)->ticks.actuator, -1);
  assembly.chainState(5, chain(5.0));
  assembly.chainState(3, chain(3.0));  // arrives late: older than what we have
  const AssembledInputs in = assembly.newest(6, 0.006, q).value();
  EXPECT_EQ(in.inputs.xi, chain(5.0));
  EXPECT_EQ(in.ticks.actuator, 5);
}

TEST(InputAssembly, FlexibleJointsTakeTheMotorSampleOfTheTick) {
  InputAssembly assembly({0, true, true}, Eigen::MatrixXd(), motor(-1.0, 2));
  const AssembledInputs before = assembly.newest(0, 0.0, q).value();  // realtime, before any PLANT_MOTOR
  EXPECT_EQ(before.inputs.motor_q, motor(-1.0, 1).row(0).transpose());
  EXPECT_EQ(before.ticks.motor, -1);
  EXPECT_FALSE(assembly.forTick(0, 0.0, q).has_value());  // lockstep: PLANT_MOTOR 0 not here
  Eigen::MatrixXd sample(2, 3);
  sample << 1, 2, 3, 4, 5, 6;
  assembly.motorSample(0, sample);
  const auto in = assembly.forTick(0, 0.0, q);
  ASSERT_TRUE(in.has_value());
  EXPECT_EQ(in->inputs.motor_q, Eigen::Vector3d(1, 2, 3));
  ASSERT_TRUE(in->inputs.motor_qdot.has_value());
  EXPECT_EQ(*in->inputs.motor_qdot, Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(in->ticks.motor, 0);
  EXPECT_EQ(in->ticks.actuator, -1);
  EXPECT_EQ(in->inputs.xi.size(), 0);  // not declared, not given
}

TEST(InputAssembly, AMotorSampleWithoutTheRateARateSensorPromisesIsRefused) {
  EXPECT_THROW(InputAssembly({0, true, true}, Eigen::MatrixXd(), motor(0.0, 1)), std::invalid_argument);
  InputAssembly assembly({0, true, true}, Eigen::MatrixXd(), motor(0.0, 2));
  try {
    assembly.motorSample(3, motor(1.0, 1));
    FAIL() << "a one-row sample was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("has 1 rows, expected 2"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(assembly.forTick(3, 0.003, q).has_value());  // and it was not kept
}

TEST(InputAssembly, MeasuredRatesPairWithThePositionOfTheirOwnTickInBothWirings) {
  Needs needs;
  needs.joint_rates = true;
  InputAssembly assembly(needs, Eigen::MatrixXd(), Eigen::MatrixXd());
  EXPECT_FALSE(assembly.forTick(0, 0.0, q).has_value());  // lockstep: PLANT_RATE 0 not here
  EXPECT_FALSE(assembly.newest(0, 0.0, q).has_value());   // realtime: not answered either
  assembly.rateSample(1, Eigen::Vector3d(7, 8, 9));       // the next tick's rate
  EXPECT_FALSE(assembly.newest(0, 0.0, q).has_value());   // ... is not tick 0's
  assembly.rateSample(0, Eigen::Vector3d(1, 2, 3));
  const auto lockstep = assembly.forTick(0, 0.0, q);
  ASSERT_TRUE(lockstep.has_value());
  EXPECT_EQ(lockstep->inputs.qdot, Eigen::Vector3d(1, 2, 3));
  const auto realtime = assembly.newest(1, 0.001, q);
  ASSERT_TRUE(realtime.has_value());
  EXPECT_EQ(realtime->inputs.qdot, Eigen::Vector3d(7, 8, 9));
  EXPECT_EQ(realtime->inputs.motor_q.size(), 0);  // not declared, not given
}

TEST(InputAssembly, APositionOnlyControllerIsAnsweredAtOnceWithQAlone) {
  InputAssembly assembly({0, false, false}, Eigen::MatrixXd(), Eigen::MatrixXd());
  for (int64_t k : {0, 7, 3}) {
    const auto in = assembly.forTick(k, 0.001 * k, q);
    ASSERT_TRUE(in.has_value());
    EXPECT_EQ(in->inputs.q, q);
    EXPECT_EQ(in->inputs.xi.size(), 0);
    EXPECT_EQ(in->inputs.motor_q.size(), 0);
    EXPECT_EQ(in->ticks.actuator, -1);
    EXPECT_EQ(in->ticks.motor, -1);
  }
}

}  // namespace
}  // namespace lagrange::controller
