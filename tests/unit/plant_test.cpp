// The ODE plant against the analytic model integrated by RK4, energy drift
// without input, and continuous multi-turn angles.
#include <gtest/gtest.h>

#include "plant/planar_chain_world.hpp"
#include "plant/plant_sim.hpp"
#include "support/rk4.hpp"

namespace lagrange::plant {
namespace {

// Torque profile held over 1 ms periods, rich enough to move every joint.
Eigen::VectorXd probeTorque(int n, double t) {
  Eigen::VectorXd tau(n);
  for (int i = 0; i < n; ++i) tau(i) = (3.0 - i) * std::sin((2.0 + i) * t + i);
  return tau;
}

// Max |q_engine - q_rk4| over 1 s from the same state under the same torque.
double gapOverOneSecond(const model::ChainParams& params, double physics_step,
                        const EngineChoice& engine = {}) {
  const int n = static_cast<int>(params.links.size());
  const model::PlanarChain chain(params);
  Eigen::VectorXd q0(n), v0(n);
  for (int i = 0; i < n; ++i) {
    q0(i) = 0.5 - 0.3 * i;
    v0(i) = 0.2 * i - 0.4;
  }
  PlantSim sim(planarChainWorld(params), {q0, v0}, physics_step, std::nullopt, std::nullopt, {}, engine);
  Eigen::VectorXd x(2 * n);
  x << q0, v0;
  const double period = 1e-3;
  const int substeps = static_cast<int>(std::lround(period / physics_step));
  double gap = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const Eigen::VectorXd tau = probeTorque(n, k * period);
    sim.step(tau, substeps);
    for (int s = 0; s < 20; ++s) x = testing::armStep(chain, x, tau, period / 20);
    gap = std::max(gap, (sim.state().q - x.head(n)).cwiseAbs().maxCoeff());
  }
  return gap;
}

TEST(PlantSim, MatchesTheAnalyticModelAndConvergesWithTheStep) {
  const double coarse = gapOverOneSecond(model::pelicanParams(), 1e-4);
  const double fine = gapOverOneSecond(model::pelicanParams(), 1e-5);
  RecordProperty("gap_1e-4", std::to_string(coarse));
  RecordProperty("gap_1e-5", std::to_string(fine));
  std::printf("ODE vs RK4 over 1 s: max |dq| = %.3e rad at dt = 1e-4, %.3e at 1e-5\n", coarse, fine);
  // ODE's stepper is first order (semi-implicit Euler): the gap is O(dt),
  // a few mrad per second of open-loop motion at the default step.
  EXPECT_LT(coarse, 5e-3);
  EXPECT_LT(fine, coarse / 5);  // ~10x smaller for a 10x smaller step
}

TEST(PlantSim, ThreeLinkChainMatchesTheModelToo) {
  model::ChainParams p;
  p.links = {{0.3, 0.15, 3.0, 0.0225}, {0.3, 0.15, 2.0, 0.015}, {0.3, 0.15, 1.0, 0.0075}};
  EXPECT_LT(gapOverOneSecond(p, 1e-4), 2e-3);
}

// MuJoCo (generalized coordinates, RK4) at the control rate's own step
// against the same equations: what ODE needs 1e-5 s for, it does at 1e-3 s.
TEST(PlantSim, OnMujocoChainsMatchTheAnalyticModelAtTheControlRatesOwnStep) {
  const EngineChoice mujoco{"mujoco", MujocoIntegrator::kRk4};
  model::ChainParams three;
  three.links = {{0.3, 0.15, 3.0, 0.0225}, {0.3, 0.15, 2.0, 0.015}, {0.3, 0.15, 1.0, 0.0075}};
  const double pelican = gapOverOneSecond(model::pelicanParams(), 1e-3, mujoco);
  const double chain3 = gapOverOneSecond(three, 1e-3, mujoco);
  const double euler = gapOverOneSecond(model::pelicanParams(), 1e-4, {"mujoco", MujocoIntegrator::kEuler});
  std::printf(
      "MuJoCo vs RK4 over 1 s: max |dq| = %.3e (Pelican), %.3e (3 links) at RK4 1e-3; %.3e at Euler 1e-4\n",
      pelican, chain3, euler);
  EXPECT_LT(pelican, 1e-7);
  EXPECT_LT(chain3, 1e-7);
  // Its semi-implicit Euler is first order like ODE's stepper: the same mrad.
  EXPECT_LT(euler, 5e-3);
  EXPECT_GT(euler, 100 * pelican);
}

// The largest chain a scenario allows, 16 links, on MuJoCo: the generated
// model nests 16 bodies, and still follows the equations at the control rate.
TEST(PlantSim, OnMujocoTheLongestChainMatchesTheAnalyticModel) {
  model::ChainParams sixteen;
  for (int i = 0; i < 16; ++i) sixteen.links.push_back({0.2, 0.1, 1.0, 0.05});
  const double gap = gapOverOneSecond(sixteen, 1e-3, {"mujoco", MujocoIntegrator::kRk4});
  std::printf("MuJoCo vs RK4 over 1 s, 16 links: max |dq| = %.3e rad at RK4 1e-3\n", gap);
  EXPECT_LT(gap, 1e-4);
}

TEST(PlantSim, EnergyDriftWithoutTorqueIsSmallAndShrinksWithTheStep) {
  auto drift = [](double dt) {
    PlantSim sim(planarChainWorld(model::pelicanParams()),
                 {Eigen::Vector2d(1.0, -0.5), Eigen::Vector2d(2.0, 1.0)}, dt);
    const double e0 = sim.energy().total();
    double worst = 0.0;
    const int substeps = static_cast<int>(std::lround(1e-3 / dt));
    for (int k = 0; k < 5000; ++k) {  // 5 s
      sim.step(Eigen::Vector2d::Zero(), substeps);
      worst = std::max(worst, std::abs(sim.energy().total() - e0));
    }
    return worst / std::abs(e0);
  };
  const double coarse = drift(1e-4), fine = drift(1e-5);
  std::printf("relative energy drift over 5 s without torque: %.3e at dt = 1e-4, %.3e at 1e-5\n", coarse,
              fine);
  EXPECT_LT(coarse, 1e-2);
  EXPECT_LT(fine, coarse / 3);
}

TEST(PlantSim, EnergyAgreesWithTheAnalyticModel) {
  const model::PlanarChain chain(model::pelicanParams());
  const Eigen::Vector2d q(0.7, 2.1), v(-1.5, 3.0);
  for (const std::string engine : {"ode", "mujoco"}) {
    PlantSim sim(planarChainWorld(model::pelicanParams()), {q, v}, 1e-4, std::nullopt, std::nullopt, {},
                 {engine});
    EXPECT_NEAR(sim.energy().kinetic, chain.kineticEnergy(q, v), 1e-12) << engine;
    EXPECT_NEAR(sim.energy().potential, chain.potentialEnergy(q), 1e-12) << engine;
    EXPECT_EQ(sim.engineName(), engine == "ode" ? "ODE" : "MuJoCo");
  }
}

TEST(PlantSim, OneLinkSpinsThroughManyTurnsWithoutWrapping) {
  model::ChainParams p;
  p.links = {{0.3, 0.15, 1.0, 0.01}};
  p.gravity = 0.0;
  PlantSim sim(planarChainWorld(p), {Eigen::VectorXd::Constant(1, 100.0), Eigen::VectorXd::Constant(1, 30.0)},
               1e-4);
  EXPECT_DOUBLE_EQ(sim.state().q(0), 100.0);
  sim.step(Eigen::VectorXd::Zero(1), 20000);  // 2 s: about 9.5 turns
  // A wrapped angle would be off by a multiple of 2 pi; what remains is the
  // first-order stepper's slight loss of speed on a link spinning about an
  // offset centre of mass (about 2 mrad here).
  EXPECT_NEAR(sim.state().q(0), 160.0, 1e-2);
  // MuJoCo integrates the angle itself: no turn is lost, and no speed.
  PlantSim mujoco(planarChainWorld(p),
                  {Eigen::VectorXd::Constant(1, 100.0), Eigen::VectorXd::Constant(1, 30.0)}, 1e-4,
                  std::nullopt, std::nullopt, {}, {"mujoco"});
  mujoco.step(Eigen::VectorXd::Zero(1), 20000);
  EXPECT_NEAR(mujoco.state().q(0), 160.0, 1e-9);
  EXPECT_NEAR(mujoco.state().qdot(0), 30.0, 1e-12);
}

// No artificial limit on the state: a link at 3e4 rad/s (three times the old
// fixed 1e4 limit) is simulated, turns counted; only the simulation's own
// limit, pi/2 per physics step, stops a run, with a named error; and a user's
// plant.max_rate stops it where the user said.
TEST(PlantSim, FastMotionRunsUntilTheStepCannotResolveIt) {
  model::ChainParams p;
  p.links = {{0.3, 0.15, 1.0, 0.01}};
  p.gravity = 0.0;
  const double h = 2.5e-5, resolvable = PlantSim::kMaxTurnPerStep / h;  // 62 832 rad/s
  // Not stopped (the old fixed limit threw here). ODE does not follow such a
  // rate accurately: its constraint stabilisation bleeds speed from a link
  // spinning about an offset centre of mass (measured: about 14 % in 10 ms
  // at 0.06 rad per step), so the angle only has to keep growing.
  PlantSim fast(planarChainWorld(p), {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 3e4)}, h);
  EXPECT_NO_THROW(fast.step(Eigen::VectorXd::Zero(1), 400));
  EXPECT_GT(fast.state().q(0), 20.0);
  try {
    PlantSim spun(planarChainWorld(p), {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 6e4)}, h);
    for (int k = 0; k < 100; ++k) spun.step(Eigen::VectorXd::Constant(1, 1e9), 1);  // ~3e10 rad/s^2
    FAIL() << "expected the simulation to stop past " << resolvable << " rad/s";
  } catch (const PlantStopped& e) {
    EXPECT_NE(std::string(e.what()).find("the simulation diverged"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("pi/2 per physics step"), std::string::npos) << e.what();
  }
  PlantSim limited(planarChainWorld(p), {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 3e4)}, h,
                   std::nullopt, 2e4);
  EXPECT_THROW(limited.step(Eigen::VectorXd::Zero(1), 1), PlantStopped);
  EXPECT_THROW(PlantSim(planarChainWorld(p), {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1)}, h,
                        std::nullopt, -1.0),
               std::invalid_argument);
}

TEST(PlantSim, AnglesAreContinuousAndIntegrateTheRates) {
  // Fast, coupled motion far from the first turn: every step's change of q
  // matches the rate (no 2 pi jumps), and q(T) - q(0) is the integral of q'.
  model::ChainParams p = model::pelicanParams();
  p.gravity = 0.0;
  PlantSim sim(planarChainWorld(p), {Eigen::Vector2d(100.0, -120.0), Eigen::Vector2d(30.0, -40.0)}, 1e-4);
  Eigen::VectorXd q = sim.state().q, v = sim.state().qdot, integral = Eigen::Vector2d::Zero();
  const Eigen::VectorXd q0 = q;
  const double dt = 1e-3;
  for (int k = 0; k < 2000; ++k) {
    sim.step(Eigen::Vector2d::Zero(), 10);
    const PlantState s = sim.state();
    integral += 0.5 * dt * (v + s.qdot);
    EXPECT_LT((s.q - q).cwiseAbs().maxCoeff(), 0.2) << "jump at tick " << k;
    q = s.q;
    v = s.qdot;
  }
  EXPECT_LT(((q - q0) - integral).cwiseAbs().maxCoeff(), 0.05);
  EXPECT_GT(std::abs(q(0) - q0(0)), 4 * M_PI);  // it really went round
}

TEST(PlantSim, RejectsBadInput) {
  EXPECT_THROW(PlantSim(planarChainWorld(model::pelicanParams()),
                        {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}, 1e-4),
               std::invalid_argument);
  EXPECT_THROW(PlantSim(planarChainWorld(model::pelicanParams()),
                        {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()}, 0.0),
               std::invalid_argument);
  PlantSim sim(planarChainWorld(model::pelicanParams()), {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()},
               1e-4);
  EXPECT_THROW(sim.step(Eigen::Vector3d::Zero(), 1), std::invalid_argument);
  EXPECT_THROW(sim.stepProfile(Eigen::MatrixXd::Zero(3, 2), 10),
               std::invalid_argument);  // 3 does not divide 10
}

// A torque profile (actuator.rate above the publish rate) applies row s over
// part s of the period: the same as stepping each part with that torque.
TEST(PlantSim, TorqueProfileAppliesEachRowOverItsPartOfThePeriod) {
  const PlantState start{Eigen::Vector2d(0.3, -0.2), Eigen::Vector2d(0.1, 0.0)};
  PlantSim profiled(planarChainWorld(model::pelicanParams()), start, 1e-4),
      stepped(planarChainWorld(model::pelicanParams()), start, 1e-4),
      held(planarChainWorld(model::pelicanParams()), start, 1e-4);
  Eigen::MatrixXd tau(4, 2);
  tau << 1, -1, 2, -2, 3, -3, 4, -4;
  profiled.stepProfile(tau, 20);
  for (int s = 0; s < 4; ++s) stepped.step(Eigen::VectorXd(tau.row(s).transpose()), 5);
  held.step(Eigen::Vector2d(1, -1), 20);
  EXPECT_EQ(profiled.state().q, stepped.state().q);
  EXPECT_EQ(profiled.state().qdot, stepped.state().qdot);
  EXPECT_GT((profiled.state().qdot - held.state().qdot).norm(), 1e-4);  // the later rows did act
}

}  // namespace
}  // namespace lagrange::plant
