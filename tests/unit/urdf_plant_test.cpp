// The URDF arms in ODE (plant/urdf_arm_world.hpp) against their model
// (model/urdf_arm.hpp): the initial state lands where it was put, RK4 of the
// model under the same torques, energy with neither torque nor gravity, and
// how far ODE's maximal coordinates let the joints come apart.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "model/urdf_arm.hpp"
#include "plant/plant_sim.hpp"
#include "plant/urdf_arm_world.hpp"
#include "support/rk4.hpp"

namespace lagrange::plant {
namespace {

std::shared_ptr<const model::UrdfArm> panda(double gravity = 9.81) {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/robots/panda.urdf");
  std::stringstream text;
  text << in.rdbuf();
  return model::UrdfArm::build({text.str(), "panda.urdf", "panda_link0", "panda_hand", gravity});
}

const Eigen::VectorXd kQ0 = (Eigen::VectorXd(7) << 0.1, -0.6, 0.2, -2.0, 0.3, 1.6, 0.7).finished();
const Eigen::VectorXd kV0 = (Eigen::VectorXd(7) << 0.5, -0.4, 0.3, 0.6, -0.8, 0.7, -1.0).finished();

TEST(UrdfPlant, StartsAtTheGivenStateWithTheModelsEnergy) {
  const auto arm = panda();
  PlantSim sim(urdfArmWorld(arm), {kQ0, kV0}, 1e-4);
  EXPECT_LT((sim.state().q - kQ0).norm(), 1e-9);
  EXPECT_LT((sim.state().qdot - kV0).norm(), 1e-9);
  EXPECT_NEAR(sim.energy().kinetic, arm->kineticEnergy(kQ0, kV0), 1e-9);
  EXPECT_NEAR(sim.energy().potential, arm->potentialEnergy(kQ0), 1e-9);
  EXPECT_LT(sim.jointSeparation(), 1e-12);
}

// The largest joint-angle gap between ODE at `step` and RK4 of the model
// (1e-4 s) over one second under a constant torque, gravity compensation at
// q0: the arm leaves q0 at kV0 and sags as it goes.
double gapToRk4(double step, double* separation, const EngineChoice& engine = {}) {
  const auto arm = panda();
  const Eigen::VectorXd tau = arm->gravity(kQ0);
  PlantSim sim(urdfArmWorld(arm), {kQ0, kV0}, step, std::nullopt, std::nullopt, {}, engine);
  Eigen::VectorXd x(14);
  x << kQ0, kV0;
  const double h = 1e-4;
  double gap = 0.0;
  for (int ms = 1; ms <= 1000; ++ms) {
    sim.step(tau, static_cast<int>(std::lround(1e-3 / step)));
    for (int k = 0; k < 10; ++k) x = testing::armStep(*arm, x, tau, h);
    gap = std::max(gap, (sim.state().q - x.head(7)).cwiseAbs().maxCoeff());
  }
  *separation = sim.jointSeparation();
  return gap;
}

// ODE's integrator is first order: the gap shrinks about as the step does.
// The motion is wide (the arm sags by radians within the second), so the gap
// is a fraction of a radian at 0.1 ms: docs/extending.md, "Accuracy of
// the plant", quotes the numbers.
TEST(UrdfPlant, FollowsTheModelCloserWithASmallerStep) {
  double separation[3] = {};
  const double gap[3] = {gapToRk4(1e-3, &separation[0]), gapToRk4(1e-4, &separation[1]),
                         gapToRk4(2.5e-5, &separation[2])};
  std::printf(
      "Panda, 1 s: ODE vs RK4 max |q gap| %.3g, %.3g, %.3g rad at 1, 0.1, 0.025 ms; "
      "joint separation %.3g, %.3g, %.3g m\n",
      gap[0], gap[1], gap[2], separation[0], separation[1], separation[2]);
  EXPECT_LT(gap[1], gap[0] / 5);
  EXPECT_LT(gap[2], gap[1] / 2);
  EXPECT_LT(separation[2], separation[1]);
  EXPECT_LT(separation[2], 1e-6) << "the joints stay together at the shipped step";
}

// MuJoCo's model is generated from the same bodies (plant/mujoco/): in
// generalized coordinates and RK4 it follows the model at the control
// rate's own step to 2e-5 rad, where ODE at 0.025 ms is 0.03 rad off.
TEST(UrdfPlant, OnMujocoFollowsTheModelAtTheControlRatesOwnStep) {
  const auto arm = panda();
  PlantSim start(urdfArmWorld(arm), {kQ0, kV0}, 1e-3, std::nullopt, std::nullopt, {}, {"mujoco"});
  // MuJoCo turns each inertia tensor to its principal axes (an iterative
  // eigen-solver, to about 1e-9 relative): the energy agrees to that.
  EXPECT_NEAR(start.energy().kinetic, arm->kineticEnergy(kQ0, kV0), 1e-8);
  EXPECT_NEAR(start.energy().potential, arm->potentialEnergy(kQ0), 1e-9);
  double separation = 1.0;
  const double gap = gapToRk4(1e-3, &separation, {"mujoco"});
  std::printf("Panda, 1 s: MuJoCo (RK4, 1 ms) vs RK4 of the model max |q gap| %.3g rad\n", gap);
  EXPECT_LT(gap, 1e-4);        // ODE: 0.1 rad at 0.1 ms
  EXPECT_EQ(separation, 0.0);  // a joint cannot come apart
}

TEST(UrdfPlant, KeepsItsEnergyWithoutTorqueOrGravity) {
  const auto arm = panda(0.0);
  for (double step : {1e-3, 1e-4}) {
    PlantSim sim(urdfArmWorld(arm), {kQ0, 3.0 * kV0}, step);
    const double e0 = sim.energy().kinetic;
    double drift = 0.0;
    for (int ms = 1; ms <= 1000; ++ms) {
      sim.step(Eigen::VectorXd::Zero(7), static_cast<int>(std::lround(1e-3 / step)));
      drift = std::max(drift, std::abs(sim.energy().kinetic - e0) / e0);
    }
    std::printf("Panda, no gravity, 1 s at %.0e s: relative energy drift %.3g, joint separation %.3g m\n",
                step, drift, sim.jointSeparation());
    EXPECT_LT(drift, step * 3.0) << "measured: 2.4e-3 at 1 ms, 2.3e-4 at 0.1 ms";
  }
}

}  // namespace
}  // namespace lagrange::plant
