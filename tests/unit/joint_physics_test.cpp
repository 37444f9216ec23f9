// The plant's joint damping, Coulomb friction and hard stops
// (plant/joint_effects.hpp) against closed forms, and the energy balance
// E(T) - E(0) = work of the torques - what damping and friction took.
#include <gtest/gtest.h>

#include <cmath>

#include "model/flexible_joint.hpp"
#include "plant/planar_chain_world.hpp"
#include "plant/plant_sim.hpp"

namespace lagrange::plant {
namespace {

// One link, 1 kg, centre of mass 0.25 m from the joint, 0.02 kg m^2 about it:
// 0.0825 kg m^2 about the joint.
model::ChainParams oneLink(double gravity) {
  model::ChainParams p;
  p.links = {{0.5, 0.25, 1.0, 0.02}};
  p.gravity = gravity;
  return p;
}
constexpr double kJointInertia = 0.02 + 1.0 * 0.25 * 0.25;
constexpr double kStep = 1e-4;
const Eigen::VectorXd kOne = Eigen::VectorXd::Ones(1);

TEST(JointPhysics, ViscousDampingDecaysASpinningLinkExponentially) {
  // Without gravity: I w' = -D w, w(t) = w0 exp(-D t / I).
  const double damping = 0.05, w0 = 3.0;
  JointPhysics physics;
  physics.damping = damping * kOne;
  PlantSim sim(planarChainWorld(oneLink(0.0)), {Eigen::VectorXd::Zero(1), w0 * kOne}, kStep, std::nullopt,
               std::nullopt, physics);
  for (int k = 1; k <= 10; ++k) {
    sim.step(Eigen::VectorXd::Zero(1), 1000);  // 0.1 s
    const double expected = w0 * std::exp(-damping * sim.time() / kJointInertia);
    EXPECT_NEAR(sim.state().qdot(0), expected, 1e-3 * expected) << "t = " << sim.time();
  }
  // Everything the link had went into the damper.
  const double e0 = 0.5 * kJointInertia * w0 * w0;
  EXPECT_NEAR(sim.dissipated(), e0 - sim.energy().total(), 1e-4 * e0);
}

TEST(JointPhysics, DampingIsStableFarBeyondWhatAnExplicitTermAllows) {
  // D h / I = 121: an explicit -D w would grow by 120x a step; ODE's motor stops the link.
  JointPhysics physics;
  physics.damping = 1e5 * kOne;
  PlantSim sim(planarChainWorld(oneLink(0.0)), {Eigen::VectorXd::Zero(1), 3.0 * kOne}, kStep, std::nullopt,
               std::nullopt, physics);
  sim.step(Eigen::VectorXd::Zero(1), 100);
  EXPECT_LT(std::abs(sim.state().qdot(0)), 1e-3);
}

TEST(JointPhysics, CoulombFrictionStopsASpinningLinkAtTheClosedFormAngleAndHoldsIt) {
  // I w' = -F while w > 0: stops at t = I w0 / F after turning I w0^2 / (2 F).
  const double friction = 0.4, w0 = 5.0;
  JointPhysics physics;
  physics.friction = friction * kOne;
  PlantSim sim(planarChainWorld(oneLink(0.0)), {Eigen::VectorXd::Zero(1), w0 * kOne}, kStep, std::nullopt,
               std::nullopt, physics);
  const double stop_time = kJointInertia * w0 / friction,
               stop_angle = kJointInertia * w0 * w0 / (2 * friction);
  sim.step(Eigen::VectorXd::Zero(1), static_cast<int>(0.5 * stop_time / kStep));
  EXPECT_NEAR(sim.state().qdot(0), w0 / 2, 1e-3 * w0);  // decelerating at F / I
  sim.step(Eigen::VectorXd::Zero(1), static_cast<int>(stop_time / kStep));
  EXPECT_NEAR(sim.state().q(0), stop_angle, 1e-3 * stop_angle);
  EXPECT_LT(std::abs(sim.state().qdot(0)), 1e-12);  // at rest: the solver leaves ~1e-44
  // A torque below F does not move it (stiction); one above does.
  sim.step(0.9 * friction * kOne, 1000);
  EXPECT_NEAR(sim.state().q(0), stop_angle, 1e-3 * stop_angle);
  EXPECT_LT(std::abs(sim.state().qdot(0)), 1e-9);
  sim.step(1.5 * friction * kOne, 1000);  // 0.1 s at (1.5 F - F) / I
  EXPECT_NEAR(sim.state().qdot(0), 0.5 * friction / kJointInertia * 0.1,
              1e-2 * 0.5 * friction / kJointInertia * 0.1);
}

TEST(JointPhysics, FrictionHoldsALinkAgainstGravityOnlyWhenItIsStrongEnough) {
  // Horizontal, the link's weight pulls with m g lc = 2.4525 N m.
  const double pull = 1.0 * 9.81 * 0.25;
  const Eigen::VectorXd horizontal = M_PI / 2 * kOne;
  for (const double friction : {1.2 * pull, 0.8 * pull}) {
    JointPhysics physics;
    physics.friction = friction * kOne;
    PlantSim sim(planarChainWorld(oneLink(9.81)), {horizontal, Eigen::VectorXd::Zero(1)}, kStep, std::nullopt,
                 std::nullopt, physics);
    sim.step(Eigen::VectorXd::Zero(1), 1000);
    if (friction > pull)
      EXPECT_NEAR(sim.state().q(0), horizontal(0), 1e-6);
    else  // falls at (m g lc - F) / I, slowing as it swings down
      EXPECT_LT(sim.state().q(0), horizontal(0) - 0.01);
  }
}

TEST(JointPhysics, ADampedPendulumsSwingsDecayAtTheClosedFormRate) {
  // Small swings: amplitude ~ exp(-D t / (2 I)) for light damping.
  const double damping = 0.02;
  JointPhysics physics;
  physics.damping = damping * kOne;
  PlantSim sim(planarChainWorld(oneLink(9.81)), {0.01 * kOne, Eigen::VectorXd::Zero(1)}, kStep, std::nullopt,
               std::nullopt, physics);
  // Peaks of q over the first and the last of 10 s, about 5.5 periods apart each.
  auto peakOver = [&](double seconds) {
    double peak = 0.0;
    for (int k = 0; k < static_cast<int>(seconds / 1e-3); ++k) {
      sim.step(Eigen::VectorXd::Zero(1), 10);
      peak = std::max(peak, std::abs(sim.state().q(0)));
    }
    return peak;
  };
  const double first = peakOver(1.0);
  peakOver(8.0);
  const double last = peakOver(1.0);
  // Peaks of the first and the last second lie within a period's start of 0 s and 9 s.
  const double expected = std::exp(-damping * 9.0 / (2 * kJointInertia));
  EXPECT_NEAR(last / first, expected, 0.03 * expected);
}

// Two links, both losses, a torque that keeps them moving and reversing, for
// 2 s: the energy's change, the torques' work (sum tau q' h), what the
// engine says the losses took, and what -D q' and Coulomb's F predict
// (sum (D q'^2 + F |q'|) h).
struct Balance {
  double change, work, dissipated, predicted;
};
Balance balanceUnderTorque(const EngineChoice& engine) {
  JointPhysics physics;
  physics.damping = Eigen::Vector2d(0.3, 0.05);
  physics.friction = Eigen::Vector2d(0.8, 0.2);
  const Eigen::Vector2d q0(0.4, -0.3), v0(1.0, -2.0);
  PlantSim sim(planarChainWorld(model::pelicanParams()), {q0, v0}, kStep, std::nullopt, std::nullopt, physics,
               engine);
  const double e0 = sim.energy().total();
  double work = 0.0, predicted = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double t = k * kStep;
    const Eigen::Vector2d tau(6.0 * std::sin(3.0 * t), 1.5 * std::cos(5.0 * t));
    sim.step(tau, 1);
    const Eigen::VectorXd v = sim.state().qdot;
    work += tau.dot(v) * kStep;
    predicted +=
        (physics.damping.cwiseProduct(v.cwiseAbs2()) + physics.friction.cwiseProduct(v.cwiseAbs())).sum() *
        kStep;
  }
  return {sim.energy().total() - e0, work, sim.dissipated(), predicted};
}

TEST(JointPhysics, EnergyBalanceHoldsWithDampingAndFrictionUnderTorque) {
  const Balance b = balanceUnderTorque(EngineChoice{});
  RecordProperty("dissipated", std::to_string(b.dissipated));
  ASSERT_GT(b.dissipated, 1.0);  // the losses took something worth checking
  // ODE's step keeps the balance up to its own energy error (PlantSim's
  // lossless drift test: ~1e-4 of the energy per second at this step).
  EXPECT_NEAR(b.change, b.work - b.dissipated, 2e-3 * (std::abs(b.work) + b.dissipated));
  // And what the motors took is what -D q' and Coulomb's F say.
  EXPECT_NEAR(b.dissipated, b.predicted, 2e-3 * b.predicted);
}

TEST(JointPhysics, ARotorsBearingLosesItsEnergyToo) {
  // One elastic joint, its rotor spun up against damping and friction.
  model::FlexibleParams flex{Eigen::VectorXd::Constant(1, 50.0), Eigen::VectorXd::Constant(1, 0.01)};
  JointPhysics physics;
  physics.rotor_damping = 0.01 * kOne;
  physics.rotor_friction = 0.05 * kOne;
  PlantState initial{Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1),
                     20.0 * kOne};
  PlantSim sim(planarChainWorld(oneLink(0.0)), initial, kStep, flex, std::nullopt, physics);
  const double e0 = sim.energy().total();
  sim.step(Eigen::VectorXd::Zero(1), 20000);
  ASSERT_GT(sim.dissipated(), 0.1 * e0);
  EXPECT_NEAR(sim.energy().total(), e0 - sim.dissipated(), 2e-3 * e0);
}

TEST(JointPhysics, AHardStopHoldsTheJointEvenPastAWrap) {
  // Spinning without gravity from 0 at -8 rad/s, the link meets its stop at
  // -4 rad: outside ODE's (-pi, pi] where it starts, reached after a wrap.
  JointPhysics physics;
  physics.lower = Eigen::VectorXd::Constant(1, -4.0);
  physics.upper = Eigen::VectorXd::Constant(1, 1.0);
  PlantSim sim(planarChainWorld(oneLink(0.0)), {Eigen::VectorXd::Zero(1), -8.0 * kOne}, kStep, std::nullopt,
               std::nullopt, physics);
  double lowest = 0.0;
  for (int k = 0; k < 2000; ++k) {
    sim.step(-1.0 * kOne, 10);  // and pushed against it
    lowest = std::min(lowest, sim.state().q(0));
  }
  EXPECT_GT(lowest, -4.0 - 0.02);
  EXPECT_NEAR(sim.state().q(0), -4.0, 0.01);
  // The upper stop, 1 rad: pushed back up, it stops there.
  for (int k = 0; k < 3000; ++k) sim.step(2.0 * kOne, 10);
  EXPECT_NEAR(sim.state().q(0), 1.0, 0.01);
}

// Refused before any engine is built, on every engine alike.
TEST(JointPhysics, RefusesBadValues) {
  const PlantState at_rest{Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1)};
  JointPhysics negative;
  negative.damping = -1.0 * kOne;
  JointPhysics wrong_size;
  wrong_size.friction = Eigen::Vector2d(1.0, 1.0);
  JointPhysics crossed;
  crossed.lower = kOne;
  crossed.upper = -1.0 * kOne;
  JointPhysics rotor_without_rotors;
  rotor_without_rotors.rotor_damping = kOne;
  for (const std::string engine : {"ode", "mujoco"})
    for (const JointPhysics& bad : {negative, wrong_size, crossed, rotor_without_rotors})
      EXPECT_THROW(
          PlantSim(planarChainWorld(oneLink(0.0)), at_rest, kStep, std::nullopt, std::nullopt, bad, {engine}),
          std::invalid_argument)
          << engine;
}

// The same closed forms on MuJoCo (plant/mujoco/mujoco_model.hpp): damping
// is the joint's own, friction `frictionloss` and a stop `range` -- soft
// constraints MuJoCo solves within the step, where ODE's are hard: the
// figures below are what the softness leaves, measured and bounded.
const EngineChoice kMujoco{"mujoco", MujocoIntegrator::kRk4};

TEST(JointPhysics, OnMujocoDampingDecaysAtTheClosedFormRateAndTheBalanceHolds) {
  const double damping = 0.05, w0 = 3.0;
  JointPhysics physics;
  physics.damping = damping * kOne;
  PlantSim sim(planarChainWorld(oneLink(0.0)), {Eigen::VectorXd::Zero(1), w0 * kOne}, kStep, std::nullopt,
               std::nullopt, physics, kMujoco);
  for (int k = 1; k <= 10; ++k) {
    sim.step(Eigen::VectorXd::Zero(1), 1000);
    const double expected = w0 * std::exp(-damping * sim.time() / kJointInertia);
    EXPECT_NEAR(sim.state().qdot(0), expected, 1e-9 * expected) << "t = " << sim.time();
  }
  const double e0 = 0.5 * kJointInertia * w0 * w0;
  EXPECT_NEAR(sim.dissipated(), e0 - sim.energy().total(), 1e-3 * e0);
}

TEST(JointPhysics, OnMujocoFrictionStopsASpinningLinkNearTheClosedFormAngle) {
  const double friction = 0.4, w0 = 5.0;
  JointPhysics physics;
  physics.friction = friction * kOne;
  PlantSim sim(planarChainWorld(oneLink(0.0)), {Eigen::VectorXd::Zero(1), w0 * kOne}, kStep, std::nullopt,
               std::nullopt, physics, kMujoco);
  const double stop_time = kJointInertia * w0 / friction,
               stop_angle = kJointInertia * w0 * w0 / (2 * friction);
  sim.step(Eigen::VectorXd::Zero(1), static_cast<int>(2 * stop_time / kStep));
  std::printf("MuJoCo friction: stopped at %.6f rad (closed form %.6f), %.3e rad/s left\n", sim.state().q(0),
              stop_angle, sim.state().qdot(0));
  // MuJoCo's default friction constraint (0.02 s, impedance 0.9-0.95)
  // stopped it 2.7e-4 rad past; the model's stiffer one at 1e-7.
  EXPECT_NEAR(sim.state().q(0), stop_angle, 1e-5 * stop_angle);
  EXPECT_LT(std::abs(sim.state().qdot(0)), 1e-9);
  const double e0 = 0.5 * kJointInertia * w0 * w0;
  EXPECT_NEAR(sim.dissipated(), e0 - sim.energy().total(), 1e-4 * e0);
}

TEST(JointPhysics, OnMujocoFrictionHoldsBelowItsForceAndGivesWayAbove) {
  // At rest: a torque of 0.9 F leaves it where it is (up to the creep of a
  // soft constraint), 1.5 F accelerates it at (1.5 F - F) / I.
  const double friction = 0.4;
  JointPhysics physics;
  physics.friction = friction * kOne;
  PlantSim sim(planarChainWorld(oneLink(0.0)), {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1)}, kStep,
               std::nullopt, std::nullopt, physics, kMujoco);
  sim.step(0.9 * friction * kOne, 1000);  // 0.1 s; free, it would turn 0.22 rad
  const double crept = sim.state().q(0);
  std::printf("MuJoCo stiction: 0.9 F for 0.1 s moved it %.3e rad (free: %.3f rad)\n", crept,
              0.5 * 0.9 * friction / kJointInertia * 0.01);
  // With MuJoCo's default friction constraint it crept 4.1e-4 rad (1.9 %).
  EXPECT_LT(std::abs(crept), 1e-4 * 0.5 * 0.9 * friction / kJointInertia * 0.01);
  sim.step(1.5 * friction * kOne, 1000);
  const double expected = 0.5 * friction / kJointInertia * 0.1;
  EXPECT_NEAR(sim.state().qdot(0), expected, 2e-2 * expected);
}

TEST(JointPhysics, OnMujocoEnergyBalanceHoldsWithDampingAndFrictionUnderTorque) {
  const Balance b = balanceUnderTorque(kMujoco);
  std::printf("MuJoCo balance: change %.6f, work - dissipated %.6f; dissipated %.6f, predicted %.6f\n",
              b.change, b.work - b.dissipated, b.dissipated, b.predicted);
  ASSERT_GT(b.dissipated, 1.0);
  // Measured: 1.2e-5 and 1e-7 of the scale.
  EXPECT_NEAR(b.change, b.work - b.dissipated, 1e-4 * (std::abs(b.work) + b.dissipated));
  EXPECT_NEAR(b.dissipated, b.predicted, 1e-5 * b.predicted);
}

TEST(JointPhysics, OnMujocoAStopHoldsTheJointFromEitherSide) {
  JointPhysics physics;
  physics.lower = Eigen::VectorXd::Constant(1, -4.0);
  physics.upper = Eigen::VectorXd::Constant(1, 1.0);
  PlantSim sim(planarChainWorld(oneLink(0.0)), {Eigen::VectorXd::Zero(1), -8.0 * kOne}, kStep, std::nullopt,
               std::nullopt, physics, kMujoco);
  double lowest = 0.0;
  for (int k = 0; k < 2000; ++k) {
    sim.step(-1.0 * kOne, 10);
    lowest = std::min(lowest, sim.state().q(0));
  }
  std::printf("MuJoCo stop at -4 rad: deepest %.4f rad, resting at %.4f rad\n", lowest, sim.state().q(0));
  // Soft: it gives 9e-4 rad when hit at 8 rad/s (MuJoCo's default stop: 0.09).
  EXPECT_GT(lowest, -4.0 - 5e-3);
  EXPECT_NEAR(sim.state().q(0), -4.0, 1e-3);
  for (int k = 0; k < 3000; ++k) sim.step(2.0 * kOne, 10);
  EXPECT_NEAR(sim.state().q(0), 1.0, 1e-3);
}

}  // namespace
}  // namespace lagrange::plant
