// The URDF robot kind (model/urdf_arm.hpp) against independent computations:
// the planar chain for a planar URDF, a recursive Newton-Euler written
// without KDL for the Panda and the UR5, and the properties every kind has.

#include "model/urdf_arm.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

#include "model/planar_chain.hpp"
#include "support/geometry_pose.hpp"
#include "support/robot_model_properties.hpp"
#include "support/urdf_rnea.hpp"
#include "util/error.hpp"

namespace lagrange::model {
namespace {

std::string robotFile(const std::string& name) {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/robots/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

struct ShippedArm {
  const char* file;
  const char* base;
  const char* tip;
  int dof;
};
const ShippedArm kPanda{"panda.urdf", "panda_link0", "panda_hand", 7};
const ShippedArm kUr5{"ur5_robot.urdf", "base_link", "tool0", 6};
const ShippedArm kPendulum{"double_pendulum.urdf", "base_link", "link2", 2};

std::shared_ptr<const UrdfArm> build(const ShippedArm& arm) {
  return UrdfArm::build({robotFile(arm.file), arm.file, arm.base, arm.tip, 9.81});
}

// A URDF of the planar chain `p`: joints about +x, the links hanging along -z
// at q = 0, so that its angles are the chain's (joint 1 from the downward
// vertical, counter-clockwise seen with the axis pointing at the viewer).
std::string planarUrdf(const ChainParams& p) {
  std::ostringstream x;
  x.precision(17);
  x << "<robot name='chain'><link name='base'/>";
  double offset = 0.0;  // the joint's position below the previous one
  for (size_t i = 0; i < p.links.size(); ++i) {
    const LinkParams& l = p.links[i];
    const std::string parent = i == 0 ? "base" : "link" + std::to_string(i);
    const std::string link = "link" + std::to_string(i + 1);
    x << "<link name='" << link << "'><inertial><origin xyz='0 0 " << -l.com << "'/><mass value='" << l.mass
      << "'/><inertia ixx='" << l.inertia << "' iyy='" << l.inertia << "' izz='" << 1e-3 * l.inertia
      << "' ixy='0' ixz='0' iyz='0'/></inertial></link>";
    x << "<joint name='joint" << i + 1 << "' type='continuous'><parent link='" << parent << "'/><child link='"
      << link << "'/><origin xyz='0 0 " << -offset << "'/><axis xyz='1 0 0'/></joint>";
    offset = l.length;
  }
  x << "</robot>";
  return x.str();
}

TEST(UrdfArm, APlanarUrdfIsThePlanarChainToRoundOff) {
  ChainParams p;
  p.links = {{0.45, 0.091, 23.902, 1.266}, {0.45, 0.048, 3.880, 0.093}, {0.3, 0.12, 2.5, 0.05}};
  const PlanarChain chain(p);
  const auto urdf = UrdfArm::build({planarUrdf(p), "planar", "base", "link3", p.gravity});
  ASSERT_EQ(urdf->dof(), 3);
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = testing::randomVector(rng, 3, 10.0), v = testing::randomVector(rng, 3, 5.0),
                          a = testing::randomVector(rng, 3, 5.0);
    const double scale = 1.0 + chain.inertia(q).norm();
    EXPECT_LT((urdf->inertia(q) - chain.inertia(q)).norm(), 1e-12 * scale);
    EXPECT_LT((urdf->coriolis(q, v) - chain.coriolis(q, v)).norm(), 1e-12 * scale * (1 + v.norm()));
    EXPECT_LT((urdf->gravity(q) - chain.gravity(q)).norm(), 1e-12 * (1 + chain.gravity(q).norm()));
    EXPECT_LT((urdf->inverseDynamics(q, v, a) - chain.inverseDynamics(q, v, a)).norm(),
              1e-11 * (1 + chain.inverseDynamics(q, v, a).norm()));
  }
}

TEST(UrdfArm, TheShippedDoublePendulumIsItsPlanarChain) {
  // Its links point up (+z) at q = 0 and swing about +x: the planar chain's
  // angles plus pi at joint 1. Its centres of mass lie off the joint line by
  // up to 2.2e-6 m (link1's y), which the planar chain cannot hold: the
  // agreement is to that offset, not to round-off.
  const auto urdf = build(kPendulum);
  ChainParams p;
  p.links = {{0.1, 0.036012, 0.26703, 0.00040827}, {0.1, 0.10088, 0.33238, 0.0011753}};
  const PlanarChain chain(p);
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = testing::randomVector(rng, 2, 10.0), v = testing::randomVector(rng, 2, 5.0),
                          a = testing::randomVector(rng, 2, 5.0);
    const Eigen::VectorXd q_chain = q + Eigen::Vector2d(M_PI, 0.0);
    EXPECT_LT((urdf->inertia(q) - chain.inertia(q_chain)).norm(), 1e-9);
    EXPECT_LT((urdf->inverseDynamics(q, v, a) - chain.inverseDynamics(q_chain, v, a)).norm(), 2e-5);
  }
}

TEST(UrdfArm, ThePandaAndTheUr5AgreeWithASecondDerivationToRoundOff) {
  for (const ShippedArm& arm : {kPanda, kUr5}) {
    const auto model = build(arm);
    ASSERT_EQ(model->dof(), arm.dof) << arm.file;
    const testing::UrdfRnea rnea(robotFile(arm.file), arm.base, arm.tip, 9.81);
    ASSERT_EQ(rnea.dof(), arm.dof);
    std::mt19937_64 rng(11);
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::VectorXd q = testing::randomVector(rng, arm.dof, M_PI),
                            v = testing::randomVector(rng, arm.dof, 3.0),
                            a = testing::randomVector(rng, arm.dof, 3.0);
      const Eigen::VectorXd tau = rnea.torques(q, v, a);
      EXPECT_LT((model->inverseDynamics(q, v, a) - tau).norm(), 1e-10 * (1 + tau.norm())) << arm.file;
      EXPECT_LT((model->inertia(q) - rnea.inertia(q)).norm(), 1e-10) << arm.file;
      EXPECT_LT((model->gravity(q) - rnea.gravity(q)).norm(), 1e-10 * (1 + tau.norm())) << arm.file;
      // The feedforward as one call equals its parts.
      EXPECT_LT((model->inverseDynamics(q, v, a) -
                 (model->inertia(q) * a + model->coriolisTimes(q, v, v) + model->gravity(q)))
                    .norm(),
                1e-10 * (1 + tau.norm()))
          << arm.file;
    }
  }
}

TEST(UrdfArm, EveryShippedArmHasTheRobotModelProperties) {
  std::mt19937_64 rng(5);
  for (const ShippedArm& arm : {kPanda, kUr5, kPendulum}) {
    SCOPED_TRACE(arm.file);
    const auto model = build(arm);
    EXPECT_EQ(model->kind(), "urdf");
    for (int trial = 0; trial < 5; ++trial) testing::expectRobotModelProperties(*model, rng);
  }
}

// What ROBOT_DESCRIPTION carries for the viewer: its frames, composed as the
// message says, put the tip where KDL's forward kinematics does.
// robot_model.hpp's contract: safe to call from several threads at once.
// Four threads share one Panda and recompute its terms at 100 states, 20
// times over, each from a different state than the others at the same
// moment; every value equals the one computed alone, bit for bit. (KDL's
// joints cache their last pose in mutable members: a chain shared by the
// threads handed one thread's rotation to another.)
TEST(UrdfArm, FourThreadsSharingOneArmComputeWhatOneThreadDoes) {
  const std::shared_ptr<const UrdfArm> arm = build(kPanda);
  const int n = arm->dof();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-2.5, 2.5);
  struct State {
    Eigen::VectorXd q, v, a;
  };
  std::vector<State> states(100);
  for (State& x : states) {
    x.q = Eigen::VectorXd::NullaryExpr(n, [&] { return angle(rng); });
    x.v = Eigen::VectorXd::NullaryExpr(n, [&] { return angle(rng); });
    x.a = Eigen::VectorXd::NullaryExpr(n, [&] { return angle(rng); });
  }
  // Every term, as one vector: D, C(q, v) v, g, inverse dynamics, the tip, U.
  const auto terms = [&](const State& x) {
    const Eigen::MatrixXd d = arm->inertia(x.q);
    Eigen::VectorXd all(n * n + 3 * n + 4);
    all << Eigen::Map<const Eigen::VectorXd>(d.data(), n * n), arm->coriolisTimes(x.q, x.v, x.v),
        arm->gravity(x.q), arm->inverseDynamics(x.q, x.v, x.a), arm->tipPosition(x.q),
        arm->potentialEnergy(x.q);
    return all;
  };
  std::vector<Eigen::VectorXd> alone;
  for (const State& x : states) alone.push_back(terms(x));
  std::atomic<int> differing{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int round = 0; round < 20; ++round)
        for (size_t k = 0; k < states.size(); ++k) {
          const size_t i = (k + 29 * static_cast<size_t>(t)) % states.size();
          if (terms(states[i]) != alone[i]) ++differing;
        }
    });
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(differing.load(), 0) << "of " << 4 * 20 * states.size() << " evaluations";
  // The geometry, read while the others compute, is the one read alone.
  const RobotGeometry before = arm->geometry();
  std::thread busy([&] {
    for (int round = 0; round < 50; ++round)
      for (const State& x : states) terms(x);
  });
  for (int round = 0; round < 200; ++round) {
    const RobotGeometry g = arm->geometry();
    for (size_t f = 0; f < g.frames.size(); ++f)
      if (g.frames[f].origin_xyz != before.frames[f].origin_xyz ||
          g.frames[f].origin_quat.coeffs() != before.frames[f].origin_quat.coeffs() ||
          g.frames[f].axis != before.frames[f].axis)
        ++differing;
  }
  busy.join();
  EXPECT_EQ(differing.load(), 0) << "geometry frames differed while another thread computed";
}

TEST(UrdfArm, TheGeometryPutsTheTipWhereKdlDoes) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for (const ShippedArm& arm : {kPanda, kUr5, kPendulum}) {
    const auto model = build(arm);
    const RobotGeometry g = model->geometry();
    int moving = 0;
    for (const GeometryFrame& f : g.frames) moving += f.joint >= 0;
    EXPECT_EQ(moving, arm.dof) << arm.file;
    EXPECT_FALSE(g.shapes.empty()) << arm.file;
    for (int trial = 0; trial < 10; ++trial) {
      Eigen::VectorXd q(arm.dof);
      for (int i = 0; i < arm.dof; ++i) q(i) = angle(rng);
      EXPECT_LT((testing::geometryTip(g, q) - model->tipPosition(q)).norm(), 1e-12) << arm.file;
    }
  }
  // The tip is not at the base: a geometry of zeros would pass the loop above.
  EXPECT_GT(build(kPanda)->tipPosition(Eigen::VectorXd::Zero(7)).norm(), 0.5);
}

TEST(UrdfArm, WhatIsNotAppliedOrLumpedIsSaid) {
  const auto panda = build(kPanda);
  bool fingers = false;
  for (const std::string& note : panda->notes())
    fingers = fingers || note.find("panda_finger_joint1' (prismatic) is off the chain") != std::string::npos;
  EXPECT_TRUE(fingers) << "the Panda's fingers are lumped into its hand, and the notes say so";
  const auto pendulum = build(kPendulum);
  ASSERT_FALSE(pendulum->notes().empty());
  EXPECT_NE(pendulum->notes().front().find("damping=0.05"), std::string::npos) << pendulum->notes().front();
  // The lumped mass is in the model: the hand and both fingers hang from joint 7's body.
  EXPECT_EQ(panda->bodies().size(), 7u);
  EXPECT_EQ(panda->jointNames().back(), "panda_joint7");
}

TEST(UrdfArm, BadChainsAreNamed) {
  const std::string panda = robotFile("panda.urdf");
  auto message = [&](const std::string& base, const std::string& tip) {
    try {
      UrdfArm::build({panda, "panda.urdf", base, tip, 9.81});
    } catch (const lagrange::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("panda_link0", "gripper").find("panda.urdf: no link 'gripper' (tip_link); its links: "),
            std::string::npos);
  EXPECT_NE(message("panda_link3", "panda_link1").find("is not below base_link 'panda_link3'"),
            std::string::npos);
  EXPECT_NE(message("panda_link0", "panda_leftfinger").find("joint 'panda_finger_joint1' on the chain"),
            std::string::npos);
  EXPECT_NE(message("panda_link0", "panda_link0").find("no revolute or continuous joint"), std::string::npos);
  const std::string broken = [] {
    try {
      UrdfArm::build({"<robot", "broken.urdf", "a", "b", 9.81});
    } catch (const lagrange::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  }();
  // urdfdom's own words are in the message (not on stderr).
  EXPECT_NE(broken.find("broken.urdf: not a valid URDF document (urdfdom: "), std::string::npos) << broken;
  EXPECT_NE(broken.find("Failed to"), std::string::npos) << broken;
}

// One moving link whose <inertial> is `inertial`, with a massless tool frame
// fixed to it (as URDFs write flanges: mass 0, zero tensor, accepted).
std::string oneLinkUrdf(const std::string& inertial) {
  return "<robot name='one'><link name='base'/><link name='arm'>" + inertial +
         "</link><link name='tool'><inertial><mass value='0'/><inertia ixx='0' iyy='0' izz='0' ixy='0' "
         "ixz='0' iyz='0'/></inertial></link>"
         "<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><axis xyz='0 0 1'/>"
         "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>"
         "<joint name='flange' type='fixed'><parent link='arm'/><child link='tool'/></joint></robot>";
}

std::string inertial(const std::string& mass, const std::string& ixx, const std::string& iyy,
                     const std::string& izz, const std::string& ixy = "0") {
  return "<inertial><origin xyz='0.1 0 0'/><mass value='" + mass + "'/><inertia ixx='" + ixx + "' iyy='" +
         iyy + "' izz='" + izz + "' ixy='" + ixy + "' ixz='0' iyz='0'/></inertial>";
}

std::string buildError(const std::string& xml) {
  try {
    UrdfArm::build({xml, "arm.urdf", "base", "tool", 9.81});
  } catch (const lagrange::Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(UrdfArm, BadMassesAndInertiasAreNamed) {
  // A good link builds, the massless tool frame included.
  EXPECT_EQ(buildError(oneLinkUrdf(inertial("1", "0.01", "0.02", "0.025"))), "no error");
  // A flat plate (largest moment = sum of the others) is a physical body.
  EXPECT_EQ(buildError(oneLinkUrdf(inertial("1", "0.01", "0.02", "0.03"))), "no error");
  EXPECT_NE(buildError(oneLinkUrdf(inertial("-1", "0.01", "0.02", "0.025")))
                .find("arm.urdf: link 'arm': mass -1 kg; expected a positive mass"),
            std::string::npos);
  EXPECT_NE(buildError(oneLinkUrdf(inertial("0", "0.01", "0.02", "0.025")))
                .find("link 'arm': mass 0 with a non-zero inertia tensor"),
            std::string::npos);
  // Massless throughout: nothing for the joint to move.
  EXPECT_NE(buildError(oneLinkUrdf(inertial("0", "0", "0", "0")))
                .find("arm.urdf: joint 'shoulder' moves no mass (link 'arm'"),
            std::string::npos);
  EXPECT_NE(buildError(oneLinkUrdf("")).find("joint 'shoulder' moves no mass"), std::string::npos);
  // ixy = 0.02 makes the xy block indefinite: moments 0.015 -+ 0.0206, 0.025.
  const std::string indefinite = buildError(oneLinkUrdf(inertial("1", "0.01", "0.02", "0.025", "0.02")));
  EXPECT_NE(indefinite.find("link 'arm': the inertia tensor is not positive definite (principal moments "
                            "-0.00561553, 0.025, 0.0356155 kg m^2)"),
            std::string::npos)
      << indefinite;
  EXPECT_NE(buildError(oneLinkUrdf(inertial("1", "0.01", "0.02", "0"))).find("not positive definite"),
            std::string::npos);
  const std::string triangle = buildError(oneLinkUrdf(inertial("1", "0.01", "0.02", "0.04")));
  EXPECT_NE(
      triangle.find("link 'arm': the inertia tensor's principal moments 0.01, 0.02, 0.04 kg m^2 violate "
                    "the triangle inequality"),
      std::string::npos)
      << triangle;
  // A branch off the chain is checked too: its mass is lumped into the model.
  std::string branch = oneLinkUrdf(inertial("1", "0.01", "0.02", "0.025"));
  branch.insert(branch.find("</robot>"),
                "<link name='finger'>" + inertial("-0.5", "0.01", "0.01", "0.01") +
                    "</link><joint name='grip' type='prismatic'><parent link='arm'/><child link='finger'/>"
                    "<axis xyz='1 0 0'/><limit lower='0' upper='0.1' effort='1' velocity='1'/></joint>");
  EXPECT_NE(buildError(branch).find("link 'finger': mass -0.5 kg"), std::string::npos);
}

}  // namespace
}  // namespace lagrange::model
