// The robot-model seam (model/robot_model.hpp): what every kind satisfies,
// the springs that turn any kind into its flexible-joint link model, and what
// the bounds and reports say of a kind without a closed form of C.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "controller/gain_report.hpp"
#include "model/bounds.hpp"
#include "model/joint_springs.hpp"
#include "model/planar_chain.hpp"
#include "support/geometry_pose.hpp"
#include "support/robot_model_properties.hpp"

namespace lagrange::model {
namespace {

ChainParams threeLinks() {
  ChainParams p;
  p.links = {{0.3, 0.15, 3.0, 0.02}, {0.3, 0.1, 2.0, 0.015}, {0.2, 0.1, 1.0, 0.004}};
  return p;
}

// A kind that only knows D, C and g numerically: the planar chain with its
// closed form of C hidden, as a URDF arm through a dynamics library would be.
class NumericOnly final : public RobotModel {
 public:
  explicit NumericOnly(ChainParams p) : arm_(std::move(p)) {}
  std::string kind() const override { return "numeric_only"; }
  int dof() const override { return arm_.dof(); }
  std::vector<std::string> jointNames() const override { return arm_.jointNames(); }
  Eigen::MatrixXd inertia(const Eigen::VectorXd& q) const override { return arm_.inertia(q); }
  std::vector<Eigen::MatrixXd> coriolisPerVelocity(const Eigen::VectorXd& q) const override {
    return arm_.coriolisPerVelocity(q);
  }
  Eigen::VectorXd gravity(const Eigen::VectorXd& q) const override { return arm_.gravity(q); }
  double potentialEnergy(const Eigen::VectorXd& q) const override { return arm_.potentialEnergy(q); }
  RobotGeometry geometry() const override { return arm_.geometry(); }
  Eigen::Vector3d tipPosition(const Eigen::VectorXd& q) const override { return arm_.tipPosition(q); }

 private:
  PlanarChain arm_;
};

TEST(RobotModel, EveryKindHasTheLagrangianProperties) {
  std::mt19937_64 rng(7);
  const auto chain = std::make_shared<PlanarChain>(threeLinks());
  const JointSprings springs(chain, Eigen::Vector3d(50.0, 20.0, 5.0));
  const NumericOnly numeric(threeLinks());
  for (int trial = 0; trial < 20; ++trial) {
    testing::expectRobotModelProperties(*chain, rng);
    testing::expectRobotModelProperties(springs, rng);
    testing::expectRobotModelProperties(numeric, rng);
  }
  EXPECT_EQ(chain->jointNames(), (std::vector<std::string>{"joint1", "joint2", "joint3"}));
}

// The planar chain's tip in closed form, and its geometry composed as
// ROBOT_DESCRIPTION says, agree; at q = 0 the arm hangs down -y.
TEST(PlanarChain, TheGeometryPutsTheTipWhereTheClosedFormDoes) {
  const PlanarChain chain(threeLinks());
  const RobotGeometry g = chain.geometry();
  EXPECT_LT((chain.tipPosition(Eigen::Vector3d::Zero()) - Eigen::Vector3d(0.0, -0.8, 0.0)).norm(), 1e-15);
  EXPECT_LT((chain.tipPosition(Eigen::Vector3d(M_PI / 2, 0.0, 0.0)) - Eigen::Vector3d(0.8, 0.0, 0.0)).norm(),
            1e-15);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d q(angle(rng), angle(rng), angle(rng));
    EXPECT_LT((testing::geometryTip(g, q) - chain.tipPosition(q)).norm(), 1e-14);
  }
  EXPECT_EQ(g.up, Eigen::Vector3d::UnitY());
  EXPECT_EQ(g.plane_normal, Eigen::Vector3d::UnitZ());
}

TEST(JointSprings, AddKqToGravityAndTheSpringEnergyAndNothingElse) {
  const auto chain = std::make_shared<PlanarChain>(threeLinks());
  const Eigen::Vector3d k(50.0, 20.0, 5.0);
  const JointSprings springs(chain, k);
  const Eigen::Vector3d q(0.4, -1.2, 2.0), v(1.0, -0.5, 0.25);
  EXPECT_EQ(springs.gravity(q), Eigen::VectorXd(chain->gravity(q) + k.cwiseProduct(q)));
  EXPECT_DOUBLE_EQ(springs.potentialEnergy(q), chain->potentialEnergy(q) + 0.5 * q.dot(k.cwiseProduct(q)));
  EXPECT_EQ(springs.inertia(q), chain->inertia(q));
  EXPECT_EQ(springs.coriolis(q, v), chain->coriolis(q, v));
  EXPECT_EQ(springs.kind(), "planar_chain");
  // The springs do not change C, so k_c stays the arm's, proven.
  EXPECT_EQ(coriolisBound(springs), coriolisBound(*chain));
  EXPECT_THROW(JointSprings(chain, Eigen::Vector2d(1.0, 1.0)), std::invalid_argument);
  EXPECT_THROW(JointSprings(chain, Eigen::Vector3d(1.0, 0.0, 1.0)), std::invalid_argument);
  EXPECT_THROW(JointSprings(nullptr, k), std::invalid_argument);
}

TEST(RobotModel, WithoutAClosedFormKcIsNotProvenAndTheReportSaysSo) {
  const NumericOnly numeric(threeLinks());
  const PlanarChain chain(threeLinks());
  EXPECT_FALSE(coriolisBound(numeric).has_value());
  ASSERT_TRUE(coriolisBound(chain).has_value());
  // The search sees the same C either way.
  EXPECT_EQ(coriolisLargestFound(numeric), coriolisLargestFound(chain));

  controller::GainReport r;
  r.kc = r.kc_found = coriolisLargestFound(numeric);
  r.kc_proven = false;
  r.condition =
      theorem1Condition(Eigen::Vector2d(10, 10), Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 1), r.kc, 1.0);
  const std::string text = controller::describe(r);
  EXPECT_NE(text.find("estimate: the largest ratio found"), std::string::npos) << text;
  EXPECT_NE(text.find("rests on the estimated k_c"), std::string::npos) << text;
  EXPECT_EQ(text.find("proven"), std::string::npos) << text;
}

}  // namespace
}  // namespace lagrange::model
