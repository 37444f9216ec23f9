// The physics-engine seam (plant/physics_engine.hpp) with an engine only this
// file knows -- unit point masses on their joints, q'' = tau, by
// semi-implicit Euler: what the test shows is the seam (named in a scenario,
// read, written, built, stepped), not a new dynamics -- and the seam's
// refusals, and MuJoCo's determinism and failure.
#include <gtest/gtest.h>

#include <stdexcept>

#include "config/scenario.hpp"
#include "model/planar_chain.hpp"
#include "plant/planar_chain_world.hpp"
#include "plant/robot_kinds.hpp"
#include "plant/scenario_plant.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::plant {
namespace {

class PointMasses final : public PhysicsEngine {
 public:
  explicit PointMasses(const EngineSetup& s) : state_(s.initial), h_(s.physics_step) {}
  void step(const Eigen::VectorXd& tau) override {
    state_.qdot += h_ * tau;
    state_.q += h_ * state_.qdot;
  }
  PlantState state() const override { return state_; }
  PlantEnergy energy() const override { return {0.5 * state_.qdot.squaredNorm(), 0.0}; }
  double dissipated() const override { return 0.0; }
  double fastestBodyRate() const override { return state_.qdot.cwiseAbs().maxCoeff(); }
  std::string unsound() const override {
    return state_.q.allFinite() && state_.qdot.allFinite() ? "" : "the point masses are no longer finite";
  }
  double jointSeparation() const override { return 0.0; }
  std::string name() const override { return "point masses"; }

 private:
  PlantState state_;
  double h_;
};

const bool point_masses_registered = registerPhysicsEngine(
    "test_point_masses", [](const EngineSetup& s) { return std::make_unique<PointMasses>(s); });

const std::string kEngineSeamScenario = R"(name: seam
duration: 1
robot: {preset: pelican}
initial_state: {q: [0.5, -0.5]}
reference: {type: sine, offset: [0.2, 0.1], amplitude: [0.1, 0.1], frequency: [1.0, 1.0]}
controller: {type: theorem1, kp: 60, kd: 6, a: 50, b: 50, initial_filter_state: bumpless}
)";

TEST(PhysicsEngineSeam, ATestOnlyEngineIsNamedReadWrittenBuiltAndStepped) {
  ASSERT_TRUE(point_masses_registered);
  const config::Scenario s =
      config::parseScenario(kEngineSeamScenario, "seam.yaml", {"plant.engine=test_point_masses"});
  EXPECT_EQ(s.plant.engine, "test_point_masses");
  const std::string resolved = config::toYaml(s);
  EXPECT_NE(resolved.find("engine: test_point_masses"), std::string::npos) << resolved;
  EXPECT_EQ(config::parseScenario(resolved, "resolved").plant.engine, "test_point_masses");
  PlantSim sim = plantFor(s);
  EXPECT_EQ(sim.engineName(), "point masses");
  sim.step(Eigen::Vector2d(1.0, -2.0), 1000);  // 0.1 s at 1e-4 s
  // Semi-implicit Euler from rest: q = q0 + a h^2 N (N + 1) / 2.
  const double h = s.plant.physics_step, reach = h * h * 1000 * 1001 / 2;
  EXPECT_NEAR(sim.state().q(0), 0.5 + reach, 1e-12);
  EXPECT_NEAR(sim.state().q(1), -0.5 - 2 * reach, 1e-12);
  // An ODE scenario's resolved file is as it was before engines had a key.
  const std::string ode = config::toYaml(config::parseScenario(kEngineSeamScenario, "seam.yaml"));
  EXPECT_EQ(ode.find("engine"), std::string::npos) << ode;
  EXPECT_EQ(plantFor(config::parseScenario(kEngineSeamScenario, "seam.yaml")).engineName(), "ODE");
}

TEST(PhysicsEngineSeam, AnEngineThisProgramLacksOrAStrayIntegratorIsRefusedWhenRead) {
  const std::string unknown = testing::errorOf(kEngineSeamScenario, {"plant.engine=bullet"});
  EXPECT_NE(unknown.find("plant.engine"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("no physics engine 'bullet' in this program; expected one of ode, mujoco"),
            std::string::npos)
      << unknown;
  const std::string stray = testing::errorOf(kEngineSeamScenario, {"plant.mujoco_integrator=euler"});
  EXPECT_NE(stray.find("plant.mujoco_integrator"), std::string::npos) << stray;
  EXPECT_NE(stray.find("plant.engine is ode"), std::string::npos) << stray;
  const std::string bad =
      testing::errorOf(kEngineSeamScenario, {"plant.engine=mujoco", "plant.mujoco_integrator=verlet"});
  EXPECT_NE(bad.find("verlet"), std::string::npos) << bad;
  const config::Scenario ok = config::parseScenario(
      kEngineSeamScenario, "seam.yaml", {"plant.engine=mujoco", "plant.mujoco_integrator=implicit"});
  EXPECT_EQ(ok.plant.mujoco_integrator, config::MujocoIntegrator::kImplicit);
  const std::string resolved = config::toYaml(ok);
  EXPECT_NE(resolved.find("mujoco_integrator: implicit"), std::string::npos) << resolved;
  EXPECT_THROW(
      registerPhysicsEngine("mujoco", [](const EngineSetup& s) { return std::make_unique<PointMasses>(s); }),
      std::logic_error);
}

TEST(PhysicsEngineSeam, MujocoRefusesAnArmDescribedForOdeOnlyNamingTheEngine) {
  ArmBuilder ode_only = planarChainWorld(model::pelicanParams());
  ode_only.bodies.reset();
  try {
    PlantSim sim(ode_only, {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()}, 1e-4, std::nullopt,
                 std::nullopt, {}, {"mujoco"});
    ADD_FAILURE() << "built";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("plant.engine: mujoco cannot simulate this arm"), std::string::npos)
        << e.what();
  }
}

// Same inputs, same doubles: what makes inproc equal lockstep and a log
// replay bit for bit -- with friction and stops, whose constraint solver
// starts from the last step's answer.
TEST(PhysicsEngineSeam, MujocoIsDeterministic) {
  JointPhysics physics;
  physics.damping = Eigen::Vector2d(0.3, 0.05);
  physics.friction = Eigen::Vector2d(0.8, 0.2);
  physics.lower = Eigen::Vector2d(-1.0, -1.5);
  physics.upper = Eigen::Vector2d(1.0, 1.5);
  auto run = [&] {
    PlantSim sim(planarChainWorld(model::pelicanParams()),
                 {Eigen::Vector2d(0.4, -0.3), Eigen::Vector2d(1.0, -2.0)}, 1e-4, std::nullopt, std::nullopt,
                 physics, {"mujoco"});
    for (int k = 0; k < 2000; ++k)
      sim.step(Eigen::Vector2d(6.0 * std::sin(3e-3 * k), 1.5 * std::cos(5e-3 * k)), 10);
    return sim.state();
  };
  const PlantState a = run(), b = run();
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.qdot, b.qdot);
}

// A closed loop gone unstable is stopped by the plant, naming MuJoCo: past
// a quarter turn per step, or at MuJoCo's own alarm -- which mj_step
// answers by resetting the arm to its start, a restart the run must not take
// for motion.
std::string stoppedBy(double torque) {
  PlantSim sim(planarChainWorld(model::pelicanParams()), {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()},
               1e-4, std::nullopt, std::nullopt, {}, {"mujoco"});
  try {
    for (int k = 0; k < 1000; ++k) sim.step(Eigen::Vector2d(torque, -torque), 10);
  } catch (const PlantStopped& e) {
    return e.what();
  }
  return "(not stopped)";
}

TEST(PhysicsEngineSeam, MujocoDivergingIsStoppedNamingTheEngine) {
  const std::string fast = stoppedBy(1e6);
  EXPECT_NE(fast.find("more than pi/2 per physics step"), std::string::npos) << fast;
  EXPECT_NE(fast.find("which MuJoCo cannot integrate"), std::string::npos) << fast;
  const std::string alarm = stoppedBy(1e12);
  EXPECT_NE(alarm.find("MuJoCo found its accelerations no longer finite or beyond 1e10"), std::string::npos)
      << alarm;
}

}  // namespace
}  // namespace lagrange::plant
