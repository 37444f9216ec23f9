// A plant the controller does not know (model/plant_perturbation.hpp): a
// payload's gravity torque at rest against the closed form, and the model
// error's seeded, bounded draws.
#include "model/plant_perturbation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "plant/planar_chain_world.hpp"
#include "plant/plant_sim.hpp"
#include "plant/urdf_arm_world.hpp"
#include "support/configs.hpp"
#include "support/scenario_text.hpp"

namespace lagrange::model {
namespace {

TEST(PlantPerturbation, APayloadsGravityTorqueAtRestIsTheClosedForm) {
  // The Pelican with 1.5 kg at 0.2 m along its last link, held at q by the
  // nominal gravity torque plus the payload's, closed form for the chain
  // (positions (sin phi, -cos phi) from the joints, phi the absolute angle):
  //   tau_1 = m g (l1 sin q1 + r sin(q1 + q2)), tau_2 = m g r sin(q1 + q2).
  const ChainParams nominal = pelicanParams();
  const Payload payload{1.5, Eigen::Vector3d(0.2, 0, 0)};
  const Eigen::Vector2d q(0.7, -1.1);
  const double g = nominal.gravity, l1 = nominal.links[0].length, r = 0.2, m = 1.5;
  const Eigen::Vector2d payload_torque(m * g * (l1 * std::sin(q(0)) + r * std::sin(q(0) + q(1))),
                                       m * g * r * std::sin(q(0) + q(1)));
  const PerturbedChain plant = perturbedChain(nominal, payload, std::nullopt);
  // The perturbed chain's own gravity is the nominal's plus the closed form.
  EXPECT_LT((PlanarChain(plant.params).gravity(q) - PlanarChain(nominal).gravity(q) - payload_torque).norm(),
            1e-12);
  // And in ODE the arm stays at rest under that torque, and falls without the payload's part.
  auto drift = [&](const Eigen::Vector2d& tau) {
    plant::PlantSim sim(plant::planarChainWorld(plant.params), {q, Eigen::Vector2d::Zero()}, 1e-4);
    sim.step(tau, 1000);
    return (sim.state().q - q).norm();
  };
  const Eigen::Vector2d nominal_torque = PlanarChain(nominal).gravity(q);
  EXPECT_LT(drift(nominal_torque + payload_torque), 1e-6);
  EXPECT_GT(drift(nominal_torque), 1e-2);
}

TEST(PlantPerturbation, AUrdfPayloadAddsItsMassAtItsPointInTheTipsFrame) {
  const config::Scenario s = config::loadScenario(testing::kConfigs + "/panda_theorem1.yaml");
  const UrdfArm& panda = *s.urdf_model;
  const Payload payload{2.0, Eigen::Vector3d(0.0, 0.0, 0.1)};
  const PerturbedBodies plant = perturbedBodies(panda, payload, std::nullopt);
  const UrdfBody &before = panda.bodies().back(), &after = plant.bodies.back();
  EXPECT_DOUBLE_EQ(after.mass, before.mass + 2.0);
  // The merged centre of mass: the weighted mean of the link's and the payload's.
  const Eigen::Vector3d at = panda.tipFrame(Eigen::VectorXd::Zero(7)) * payload.com;
  EXPECT_LT((after.com - (before.mass * before.com + 2.0 * at) / after.mass).norm(), 1e-12);
  // Held at rest in ODE by the nominal gravity torque plus the payload's,
  // from the virtual work of its weight: tau_j = m g e_z . dp/dq_j, with p
  // the payload's point by KDL's forward kinematics, differentiated centrally.
  const Eigen::VectorXd q = (Eigen::VectorXd(7) << 0.3, -0.5, 0.2, -1.8, 0.1, 1.5, 0.4).finished();
  Eigen::VectorXd payload_torque(7);
  for (int j = 0; j < 7; ++j) {
    Eigen::VectorXd dq = Eigen::VectorXd::Zero(7);
    dq(j) = 1e-6;
    const Eigen::Vector3d dp =
        (panda.tipFrame(q + dq) * payload.com - panda.tipFrame(q - dq) * payload.com) / 2e-6;
    payload_torque(j) = 2.0 * panda.spec().gravity * dp.z();
  }
  auto drift = [&](const Eigen::VectorXd& tau) {
    plant::PlantSim sim(plant::urdfArmWorld(plant.bodies, panda.spec().gravity),
                        {q, Eigen::VectorXd::Zero(7)}, 1e-4);
    sim.step(tau, 1000);
    return (sim.state().q - q).norm();
  };
  EXPECT_LT(drift(panda.gravity(q) + payload_torque), 1e-4);
  EXPECT_GT(drift(panda.gravity(q)), 1e-2);
}

TEST(PlantPerturbation, ModelErrorIsSeededBoundedAndOnlyWhatItSays) {
  const ChainParams nominal = pelicanParams();
  const ModelError error{0.2, 0.1, 0.05, 7};
  const PerturbedChain a = perturbedChain(nominal, std::nullopt, error),
                       b = perturbedChain(nominal, std::nullopt, error);
  ModelError other = error;
  other.seed = 8;
  const PerturbedChain c = perturbedChain(nominal, std::nullopt, other);
  bool differs = false;
  for (size_t i = 0; i < nominal.links.size(); ++i) {
    const LinkParams &n = nominal.links[i], &p = a.params.links[i];
    EXPECT_EQ(p.mass, b.params.links[i].mass);  // the same seed, the same plant
    differs = differs || p.mass != c.params.links[i].mass;
    EXPECT_LE(std::abs(p.mass / n.mass - 1.0), 0.2);
    EXPECT_LE(std::abs(p.inertia / n.inertia - 1.0), 0.1);
    EXPECT_LE(std::abs(p.com / n.com - 1.0), 0.05);
    EXPECT_NE(p.mass, n.mass);
    EXPECT_EQ(p.length, n.length);  // not perturbed
    EXPECT_EQ(a.changes[i].mass, p.mass);
  }
  EXPECT_TRUE(differs);
  EXPECT_THROW(perturbedChain(nominal, std::nullopt, ModelError{1.0, 0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(perturbedChain(nominal, Payload{-1.0, Eigen::Vector3d::Zero()}, std::nullopt),
               std::invalid_argument);
}

TEST(PlantPerturbation, TheKeysReadWriteAndRefuse) {
  const config::Scenario s = config::loadScenario(
      testing::kRigid, {"plant.payload={mass: 1.0, com: 0.2}", "plant.model_error={mass: 0.1, seed: 4}"});
  ASSERT_TRUE(s.plant.payload && s.plant.model_error);
  EXPECT_EQ(s.plant.payload->com.x(), 0.2);
  EXPECT_EQ(s.plant.model_error->seed, 4u);
  const config::Scenario again = config::parseScenario(config::toYaml(s), "resolved.yaml");
  EXPECT_EQ(again.plant.payload->mass, 1.0);
  EXPECT_EQ(again.plant.model_error->mass, 0.1);
  const std::string rigid = testing::readFile(testing::kRigid);
  EXPECT_NE(
      testing::errorOf(rigid, {"plant.payload={mass: -1}"}).find("plant.payload.mass: expected a mass >= 0"),
      std::string::npos);
  EXPECT_NE(testing::errorOf(rigid, {"plant.payload={mass: 1, com: [0, 0, 1]}"})
                .find("plant.payload.com: the planar chain's payload sits on its last link"),
            std::string::npos);
  EXPECT_NE(testing::errorOf(rigid, {"plant.model_error={mass: 0.95}"}).find("plant.model_error.mass"),
            std::string::npos)
      << testing::errorOf(rigid, {"plant.model_error={mass: 0.95}"});
  EXPECT_NE(
      testing::errorOf(rigid, {"plant.model_error={mas: 0.1}"}).find("plant.model_error.mas: unknown key"),
      std::string::npos)
      << testing::errorOf(rigid, {"plant.model_error={mas: 0.1}"});
}

}  // namespace
}  // namespace lagrange::model
