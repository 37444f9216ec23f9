// lagrange view's FrameAssembler: PLANT_TRUTH, CONTROL_COMMAND and
// PLANT_MOTOR joined by tick, in whatever order they arrive.
#include "tools/view/view_frames.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "config/robot_description_lcm.hpp"
#include "config/scenario.hpp"

namespace lagrange::tools {
namespace {

lagrange::plant_truth_t truth(int64_t tick, std::vector<double> q) {
  lagrange::plant_truth_t m{};
  m.header.tick = tick;
  m.header.sim_time = 0.001 * static_cast<double>(tick);
  m.num_joints = static_cast<int32_t>(q.size());
  m.q = q;
  m.qdot.assign(q.size(), 0.0);
  m.tau_applied.assign(q.size(), 1.0 + static_cast<double>(tick));
  return m;
}

lagrange::control_command_t command(int64_t tick, std::vector<double> q_desired) {
  lagrange::control_command_t m{};
  m.header.tick = tick;
  m.input_position_tick = tick;
  m.num_joints = static_cast<int32_t>(q_desired.size());
  m.q_desired = q_desired;
  return m;
}

lagrange::plant_motor_t motor(int64_t tick, std::vector<double> q) {
  lagrange::plant_motor_t m{};
  m.header.tick = tick;
  m.num_joints = static_cast<int32_t>(q.size());
  m.q = q;
  return m;
}

TEST(FrameAssembler, JoinsByTickWhateverTheOrder) {
  FrameAssembler a;
  a.add(command(1, {0.5, 0.5}));  // before its truth
  a.add(truth(0, {0.0, 0.0}));
  a.add(truth(1, {3.5, 4.5}));
  a.add(motor(1, {9.0, 8.0}));
  a.add(command(0, {0.0, 0.0}));  // after the truth of the next tick
  // Tick 1 waits: its messages may not all be in until a newer truth comes.
  std::vector<ViewFrame> ready = a.take(false);
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].tick, 0);
  EXPECT_EQ(ready[0].q_desired, (std::vector<double>{0.0, 0.0}));
  EXPECT_TRUE(ready[0].motor.empty());
  EXPECT_EQ(ready[0].error_norm, 0.0);
  ready = a.take(true);
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].tick, 1);
  EXPECT_EQ(ready[0].t, 0.001);
  EXPECT_EQ(ready[0].q_desired, (std::vector<double>{0.5, 0.5}));
  EXPECT_EQ(ready[0].motor, (std::vector<double>{9.0, 8.0}));
  EXPECT_EQ(ready[0].tau, (std::vector<double>{2.0, 2.0}));
  EXPECT_DOUBLE_EQ(ready[0].error_norm, 5.0);  // |(3, 4)|
}

TEST(FrameAssembler, AMissingCommandTakesTheNewestBeforeAndRetransmissionsAreDropped) {
  FrameAssembler a;
  a.add(truth(0, {1.0}));
  EXPECT_TRUE(std::isnan(a.take(true).at(0).error_norm));  // no reference yet
  a.add(command(1, {0.25}));
  a.add(truth(1, {1.0}));
  a.add(truth(2, {2.0}));  // its command lost
  a.add(truth(3, {3.0}));
  const std::vector<ViewFrame> ready = a.take(false);
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_EQ(ready[1].tick, 2);
  EXPECT_EQ(ready[1].q_desired, (std::vector<double>{0.25}));
  a.add(truth(2, {-7.0}));  // a retransmission of a tick already taken
  const std::vector<ViewFrame> rest = a.take(true);
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_EQ(rest[0].tick, 3);
  EXPECT_TRUE(a.take(true).empty());
}

TEST(FrameAssembler, FramesAsColumnsWithNullForMissingValues) {
  FrameAssembler a;
  a.add(truth(0, {1.0, 2.0}));
  const nlohmann::json j = framesJson(a.take(true));
  EXPECT_EQ(j["t"], nlohmann::json::array({0.0}));
  EXPECT_EQ(j["q"][0], nlohmann::json::array({1.0, 2.0}));
  EXPECT_TRUE(j["q_desired"][0].is_null());
  EXPECT_TRUE(j["motor"][0].is_null());
  EXPECT_TRUE(j["error_norm"][0].is_null());
}

}  // namespace
}  // namespace lagrange::tools

namespace lagrange::tools {
namespace {

TEST(RobotDescription, TheShippedArmsAreDrawableAndBrokenOnesAreNamed) {
  for (const char* config : {"rigid_2dof.yaml", "flexible_2dof.yaml", "panda_theorem1.yaml"}) {
    const config::Scenario s = config::loadScenario(std::string(LAGRANGE_SOURCE_DIR) + "/configs/" + config);
    const lagrange::robot_description_t d = config::robotDescriptionMessage(s);
    EXPECT_EQ(descriptionProblem(d), "") << config;
    EXPECT_EQ(d.flexible, s.flexible.has_value()) << config;
    EXPECT_EQ(d.num_joints, s.dof()) << config;
  }
  const config::Scenario s =
      config::loadScenario(std::string(LAGRANGE_SOURCE_DIR) + "/configs/rigid_2dof.yaml");
  const lagrange::robot_description_t good = config::robotDescriptionMessage(s);
  lagrange::robot_description_t d = good;
  d.frame_parent[0] = 1;  // a parent after its child: the page would build a cycle
  EXPECT_EQ(descriptionProblem(d), "frame 0's parent does not come before it");
  d = good;
  d.frame_joint[1] = 2;
  EXPECT_EQ(descriptionProblem(d), "frame 1's joint is not one of the 2 joints");
  d = good;
  d.frame_quat[0] = {2.0, 0.0, 0.0, 0.0};
  EXPECT_NE(descriptionProblem(d).find("not of unit length"), std::string::npos);
  d = good;
  d.shape_type[0] = 7;
  EXPECT_EQ(descriptionProblem(d), "shape 0's type is unknown");
  d = good;
  d.num_frames = 3;
  EXPECT_EQ(descriptionProblem(d), "num_frames does not match its arrays (or is 0)");
  d = good;
  d.tip_xyz[1] = std::nan("");
  EXPECT_EQ(descriptionProblem(d), "tip_xyz is not finite");
}

}  // namespace
}  // namespace lagrange::tools
