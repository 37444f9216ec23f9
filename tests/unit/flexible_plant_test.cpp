// The flexible-joint plant (eq. 595) in ODE against the analytic 2n-DOF model
// integrated by RK4, energy conservation without input or gravity, and the
// stiff limit: K -> infinity gives the rigid arm with the rotor inertias added.
#include <gtest/gtest.h>

#include "model/flexible_joint.hpp"
#include "plant/planar_chain_world.hpp"
#include "plant/plant_sim.hpp"
#include "support/rk4.hpp"

namespace lagrange::plant {
namespace {

model::FlexibleParams flexibleParams(double k) {
  return {Eigen::Vector2d(k, 0.8 * k), Eigen::Vector2d(0.05, 0.03)};
}

PlantState start() {
  return {Eigen::Vector2d(0.5, -0.3), Eigen::Vector2d(-0.4, 0.2), Eigen::Vector2d(0.6, -0.1),
          Eigen::Vector2d(0.0, 0.5)};
}

// x = [q1, q1', q2, q2'] of (595), written from the equations.
Eigen::VectorXd flexibleField(const model::PlanarChain& chain, const model::FlexibleParams& p,
                              const Eigen::VectorXd& x, const Eigen::VectorXd& tau) {
  const int n = chain.dof();
  const Eigen::VectorXd spring = p.stiffness.cwiseProduct(x.segment(2 * n, n) - x.head(n));
  Eigen::VectorXd d(4 * n);
  d << x.segment(n, n), chain.acceleration(x.head(n), x.segment(n, n), spring), x.tail(n),
      (tau - spring).cwiseQuotient(p.rotor_inertia);
  return d;
}

Eigen::VectorXd motorTorque(double t) {
  return Eigen::Vector2d(2.0 * std::sin(3.0 * t), -1.0 + std::cos(5.0 * t));
}

// Largest |q1 - q1_rk4| and |q2 - q2_rk4| over 1 s under the same motor torque.
double gapToModel(double k, double physics_step, const EngineChoice& engine = {}) {
  const model::PlanarChain chain(model::pelicanParams());
  const model::FlexibleParams p = flexibleParams(k);
  const PlantState s0 = start();
  PlantSim sim(planarChainWorld(model::pelicanParams()), s0, physics_step, p, std::nullopt, {}, engine);
  Eigen::VectorXd x(8);
  x << s0.q, s0.qdot, s0.motor_q, s0.motor_qdot;
  const int substeps = static_cast<int>(std::lround(1e-3 / physics_step));
  double gap = 0.0;
  for (int k_tick = 0; k_tick < 1000; ++k_tick) {
    const Eigen::VectorXd tau = motorTorque(k_tick * 1e-3);
    sim.step(tau, substeps);
    auto f = [&](double, const Eigen::VectorXd& y) { return flexibleField(chain, p, y, tau); };
    for (int i = 0; i < 20; ++i) x = testing::rk4Step(f, 0.0, x, 1e-3 / 20);
    const PlantState st = sim.state();
    gap = std::max({gap, (st.q - x.head(2)).cwiseAbs().maxCoeff(),
                    (st.motor_q - x.segment(4, 2)).cwiseAbs().maxCoeff()});
  }
  return gap;
}

TEST(FlexiblePlant, MatchesTheAnalyticModelAndConvergesWithTheStep) {
  const double coarse = gapToModel(100.0, 1e-4), fine = gapToModel(100.0, 1e-5);
  std::printf("flexible plant vs RK4 of (595), K = 100 N m/rad: %.3e rad at 0.1 ms, %.3e rad at 0.01 ms\n",
              coarse, fine);
  EXPECT_LT(fine, 1e-3);
  EXPECT_LT(fine, coarse / 5);  // first-order stepper: ~10x smaller for a 10x smaller step
}

// On MuJoCo the springs are tendons of the model, inside RK4's step.
TEST(FlexiblePlant, OnMujocoMatchesTheAnalyticModelAtTheControlRatesOwnStep) {
  const double gap = gapToModel(100.0, 1e-3, {"mujoco"});
  std::printf("flexible plant on MuJoCo (RK4, 1 ms) vs RK4 of (595), K = 100 N m/rad: %.3e rad\n", gap);
  EXPECT_LT(gap, 2e-5);  // ODE: 1.7e-3 rad at 0.1 ms
}

TEST(FlexiblePlant, ModelAccelerationIsTheEquations) {
  const model::PlanarChain chain(model::pelicanParams());
  const model::FlexibleChain flexible(std::make_shared<model::PlanarChain>(chain), flexibleParams(300.0));
  const PlantState s = start();
  const Eigen::Vector2d tau(0.7, -0.2);
  const auto [a1, a2] = flexible.acceleration({s.q, s.qdot, s.motor_q, s.motor_qdot}, tau);
  Eigen::VectorXd x(8);
  x << s.q, s.qdot, s.motor_q, s.motor_qdot;
  const Eigen::VectorXd d = flexibleField(chain, flexibleParams(300.0), x, tau);
  EXPECT_LT((a1 - d.segment(2, 2)).norm(), 1e-12);
  EXPECT_LT((a2 - d.tail(2)).norm(), 1e-12);
}

TEST(FlexiblePlant, ConservesEnergyWithoutInputOrGravity) {
  model::ChainParams weightless = model::pelicanParams();
  weightless.gravity = 0.0;
  const model::FlexibleParams p = flexibleParams(200.0);
  double drift[2];
  const double steps[2] = {1e-4, 1e-5};
  for (int r = 0; r < 2; ++r) {
    PlantSim sim(planarChainWorld(weightless), start(), steps[r], p);
    const double e0 = sim.energy().total();
    const model::FlexibleChain model(std::make_shared<model::PlanarChain>(weightless), p);
    const PlantState s = start();
    EXPECT_NEAR(e0, model.energy({s.q, s.qdot, s.motor_q, s.motor_qdot}), 1e-9 * e0);  // same energy
    double worst = 0.0;
    for (int k = 0; k < 2000; ++k) {  // 2 s
      sim.step(Eigen::Vector2d::Zero(), static_cast<int>(std::lround(1e-3 / steps[r])));
      worst = std::max(worst, std::abs(sim.energy().total() - e0) / e0);
    }
    drift[r] = worst;
  }
  std::printf("relative energy drift over 2 s: %.3e at 0.1 ms, %.3e at 0.01 ms\n", drift[0], drift[1]);
  EXPECT_LT(drift[1], 1e-3);
  EXPECT_LT(drift[1], drift[0] / 3);  // the drift is the stepper's, not a leak in the model
}

// The paper's footnote to Example 1: as K grows the model tends to the rigid
// arm (10), here with the rotor inertias J added to D's diagonal, q2 = q1.
TEST(FlexiblePlant, StiffLimitIsTheRigidArmWithTheRotorInertias) {
  const model::ChainParams params = model::pelicanParams();
  const model::PlanarChain chain(params);
  auto gapToRigid = [&](double k) {
    const model::FlexibleParams p = flexibleParams(k);
    PlantState s0 = start();
    s0.motor_q = s0.q;  // no initial twist
    s0.motor_qdot = s0.qdot;
    PlantSim sim(planarChainWorld(params), s0, 1e-5, p);
    Eigen::VectorXd x(4);
    x << s0.q, s0.qdot;
    double gap = 0.0;
    for (int tick = 0; tick < 500; ++tick) {
      const Eigen::VectorXd tau = motorTorque(tick * 1e-3);
      sim.step(tau, 100);
      auto f = [&](double, const Eigen::VectorXd& y) {
        const Eigen::MatrixXd d = chain.inertia(y.head(2)) + Eigen::MatrixXd(p.rotor_inertia.asDiagonal());
        Eigen::VectorXd dy(4);
        dy << y.tail(2),
            d.ldlt().solve(tau - chain.coriolis(y.head(2), y.tail(2)) * y.tail(2) - chain.gravity(y.head(2)));
        return dy;
      };
      for (int i = 0; i < 10; ++i) x = testing::rk4Step(f, 0.0, x, 1e-4);
      gap = std::max(gap, (sim.state().q - x.head(2)).cwiseAbs().maxCoeff());
    }
    return gap;
  };
  const double soft = gapToRigid(100.0), stiff = gapToRigid(1e4), stiffer = gapToRigid(1e6);
  std::printf("flexible vs rigid + J over 0.5 s: K = 1e2 %.3e, 1e4 %.3e, 1e6 %.3e rad\n", soft, stiff,
              stiffer);
  // The gap falls with K until it reaches the floor of ODE's first-order
  // stepper at 0.01 ms (~3e-5 rad over 0.5 s, the rigid plant's own error).
  EXPECT_LT(stiff, soft / 10);
  EXPECT_LT(stiffer, 1e-4);
}

TEST(FlexiblePlant, RejectsBadParameters) {
  EXPECT_THROW(PlantSim(planarChainWorld(model::pelicanParams()), start(), 1e-4,
                        model::FlexibleParams{Eigen::Vector2d(100, 0), Eigen::Vector2d(1, 1)}),
               std::invalid_argument);
  EXPECT_THROW(PlantSim(planarChainWorld(model::pelicanParams()), start(), 1e-4,
                        model::FlexibleParams{Eigen::Vector2d(100, 100), Eigen::Vector2d(-1, 1)}),
               std::invalid_argument);
  PlantState no_motor = start();
  no_motor.motor_q.resize(0);
  EXPECT_THROW(PlantSim(planarChainWorld(model::pelicanParams()), no_motor, 1e-4, flexibleParams(100.0)),
               std::invalid_argument);
}

// A diverging loop stops with a named error instead of ODE's abort.
TEST(FlexiblePlant, DivergenceIsReportedBeforeOdeAborts) {
  PlantSim sim(planarChainWorld(model::pelicanParams()), start(), 1e-4, flexibleParams(100.0));
  try {
    for (int k = 0; k < 1000; ++k)
      sim.step(Eigen::Vector2d(1e6, -1e6), 10);  // spins everything up without bound
    FAIL() << "expected the divergence to be reported";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the simulation diverged"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lagrange::plant
