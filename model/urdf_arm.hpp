#pragma once
/// @file
/// A serial arm described in URDF, as a RobotModel (model/robot_model.hpp):
/// the chain of links between `base_link` and `tip_link`, its dynamics
/// computed by orocos KDL (recursive Newton-Euler for inverse dynamics and
/// gravity, the composite-rigid-body inertia matrix).
///
/// The chain: revolute and continuous joints are the arm's joints; fixed
/// joints on the chain stay rigid (KDL carries them as segments without a
/// joint); every branch off the chain (the Panda's fingers) is held at its
/// zero position and its mass lumped into the link it hangs from. Gravity
/// points along the URDF world's -z; base_link's frame is taken as the world
/// (a fixed base). Joint limits, damping and friction in the URDF are not
/// in this model -- it is lossless (eq. (1)), as the controllers assume --
/// but are kept per joint (jointProperties()) for the plant, which applies
/// them when the scenario asks (plant.urdf_dynamics, plant.joint_limits,
/// actuator.saturation: urdf); notes() lists them for the processes to
/// report at start.
///
/// C is the Christoffel-symbol matrix, obtained by polarisation of KDL's
/// velocity terms h(q, v) = C(q, v) v (a symmetric bilinear form in v):
///   C(q, x) y = (h(q, x + y) - h(q, x - y)) / 4,
/// so C(q, x) y = C(q, y) x and D' - 2C is skew-symmetric. The controllers'
/// feedforward D(q) a + C(q, v) v + g(q) is one recursive Newton-Euler call
/// (inverseDynamics); the full C is formed only where a caller asks for it.
///
/// The URDF is given as text: reading the file is the caller's business
/// (config), so this model stays free of I/O.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/robot_model.hpp"

namespace lagrange::model {

struct UrdfChainSpec {
  std::string xml;        ///< the URDF document
  std::string source;     ///< where it came from, for messages (a file name)
  std::string base_link;  ///< the fixed link the chain starts from
  std::string tip_link;   ///< the last link of the chain
  double gravity = 9.81;  ///< [m/s^2], along the URDF world's -z
};

/// One rigid body of the chain as the plant builds it, at q = 0, in the base
/// frame: a link with the fixed-joint children and the off-chain branches
/// lumped into it.
struct UrdfBody {
  std::string link;              ///< the link whose joint moves it
  std::string joint;             ///< its revolute or continuous joint
  Eigen::Vector3d joint_anchor;  ///< a point on the joint axis [m]
  Eigen::Vector3d joint_axis;    ///< unit vector, positive rotation by the right-hand rule
  double mass = 0.0;             ///< [kg]
  Eigen::Vector3d com;           ///< centre of mass [m]
  Eigen::Matrix3d inertia;       ///< about the centre of mass, base-frame axes [kg m^2]
};

/// What a chain joint's <dynamics> and <limit> say (absent: zero, none).
struct UrdfJointProperties {
  double damping = 0.0;            ///< <dynamics damping> [N m s/rad]
  double friction = 0.0;           ///< <dynamics friction> [N m]
  std::optional<double> lower;     ///< <limit lower> of a revolute joint [rad]
  std::optional<double> upper;     ///< <limit upper> of a revolute joint [rad]
  std::optional<double> effort;    ///< <limit effort> [N m]
  std::optional<double> velocity;  ///< <limit velocity> [rad/s]
};

class UrdfArm : public RobotModel {
 public:
  /// @throws model::Error naming the source and what is wrong: unparsable
  ///         URDF, an unknown link (the known ones listed), a tip not below
  ///         the base, a prismatic or floating joint on the chain, no joint,
  ///         a negative mass, an inertia tensor that is not positive definite
  ///         or violates the triangle inequality, a joint that moves no mass.
  static std::shared_ptr<const UrdfArm> build(const UrdfChainSpec& spec);
  ~UrdfArm() override;

  std::string kind() const override { return "urdf"; }
  int dof() const override;
  std::vector<std::string> jointNames() const override;
  Eigen::MatrixXd inertia(const Eigen::VectorXd& q) const override;
  std::vector<Eigen::MatrixXd> coriolisPerVelocity(const Eigen::VectorXd& q) const override;
  Eigen::MatrixXd coriolis(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override;
  Eigen::VectorXd coriolisTimes(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& w) const override;
  Eigen::VectorXd gravity(const Eigen::VectorXd& q) const override;
  /// sum of m_i g z_i over the bodies; zero where every centre of mass is at z = 0.
  double potentialEnergy(const Eigen::VectorXd& q) const override;
  Eigen::VectorXd inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  const Eigen::VectorXd& a) const override;

  /// What the URDF holds that the model does not apply, and what was lumped
  /// (one sentence each, for the processes to log at start).
  /// The chain's frames as the URDF gives them (fixed joints included), the
  /// tip at the origin of tip_link; shapes from model/robot_geometry.hpp
  /// (the URDF's own visuals are not read). Up is +z.
  RobotGeometry geometry() const override;
  /// The origin of tip_link, by KDL's forward kinematics.
  Eigen::Vector3d tipPosition(const Eigen::VectorXd& q) const override;
  /// tip_link's frame in the base frame (a point in tip_link's frame -> base).
  Eigen::Isometry3d tipFrame(const Eigen::VectorXd& q) const;

  const std::vector<std::string>& notes() const;
  /// Per joint, base to tip: its <dynamics> and <limit>.
  const std::vector<UrdfJointProperties>& jointProperties() const;
  /// The moving bodies, base to tip, at q = 0 (for the plant's builder).
  const std::vector<UrdfBody>& bodies() const;
  const UrdfChainSpec& spec() const;

  /// The velocity terms h(q, v) = C(q, v) v (one KDL call).
  Eigen::VectorXd velocityTerms(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

 private:
  struct Impl;
  explicit UrdfArm(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace lagrange::model
