#pragma once
/// @file
/// Rigid n-link planar revolute chain moving in a vertical plane: the plant
/// model of eq. (10), D(q) q'' + C(q, q') q' + g(q) = u.
///
/// Conventions: q_i is the angle of link i relative to link i-1 (q_1 from the
/// downward vertical), positive counter-clockwise. The absolute angle of link
/// i is phi_i = q_1 + ... + q_i, and link i points along (sin phi_i, -cos phi_i).
///
/// Derivation. Writing the centre of mass of link i as
///   p_i = sum_a c_ia (sin phi_a, -cos phi_a),  c_ia = l_a (a < i), lc_i (a = i), 0 (a > i),
/// the mass matrix in absolute angles is M_ab(phi) = I_a delta_ab + h_ab cos(phi_a - phi_b)
/// with h_ab = sum_i m_i c_ia c_ib, and D(q) = L^T M(L q) L where L is the
/// lower-triangular matrix of ones (phi = L q). The potential energy is
/// U = -g sum_a s_a cos phi_a with s_a = sum_i m_i c_ia. C is built from
/// Christoffel symbols of the first kind, so D' - 2C is skew-symmetric and
/// C(q, x) y = C(q, y) x hold by construction.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "model/robot_model.hpp"

namespace lagrange::model {

/// Physical parameters of one link.
struct LinkParams {
  double length = 0.0;   ///< l: joint-to-joint length [m]
  double com = 0.0;      ///< lc: distance from the link's joint to its centre of mass [m]
  double mass = 0.0;     ///< m [kg]
  double inertia = 0.0;  ///< I: moment of inertia about the centre of mass, normal to the plane [kg m^2]
};

/// Parameters of the whole chain (constant; Pinocchio's "Model").
struct ChainParams {
  std::vector<LinkParams> links;  ///< base to tip
  double gravity = 9.81;          ///< g [m/s^2], acting downwards in the plane of motion
};

/// The 2-DOF "Pelican" arm of Kelly, Santibanez and Loria, "Control of Robot
/// Manipulators in Joint Space", Springer 2005, Table 5.1.
ChainParams pelicanParams();

/// Dynamics of an n-link planar chain: the robot kind "planar_chain".
/// Immutable after construction; every function is pure and thread-safe.
class PlanarChain : public RobotModel {
 public:
  /// @throws std::invalid_argument if there are no links, or a length,
  ///         mass or inertia is not positive, or com is negative or not finite.
  explicit PlanarChain(ChainParams params);

  std::string kind() const override { return "planar_chain"; }
  int dof() const override { return static_cast<int>(params_.links.size()); }
  /// "joint1" .. "jointN", base to tip.
  std::vector<std::string> jointNames() const override;
  const ChainParams& params() const { return params_; }

  Eigen::MatrixXd inertia(const Eigen::VectorXd& q) const override;

  /// Partial derivatives dD/dq_k, k = 0..n-1.
  std::vector<Eigen::MatrixXd> inertiaPartials(const Eigen::VectorXd& q) const;

  /// From the Christoffel symbols of inertiaPartials.
  std::vector<Eigen::MatrixXd> coriolisPerVelocity(const Eigen::VectorXd& q) const override;

  /// The closed form of C: one term per link pair (a, b) of absolute link
  /// angles with h_ab != 0, per_velocity[k] from h_ab alone. Used for a proven
  /// bound of ||C(q, y)|| / ||y|| (model/bounds.hpp); C itself is computed by
  /// coriolisPerVelocity.
  std::optional<std::vector<CoriolisTerm>> coriolisTerms() const override;

  Eigen::VectorXd gravity(const Eigen::VectorXd& q) const override;

  /// C(q, v) w (Christoffel C) in closed form, O(n^2), without forming C:
  /// the baselines' C(q, q') q_r' every tick (the matrix is O(n^3) to build).
  Eigen::VectorXd coriolisTimes(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& w) const override;

  /// D(q) a + C(q, v) v + g(q) in closed form, O(n^2), without forming C:
  /// the controllers' feedforward every tick.
  Eigen::VectorXd inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  const Eigen::VectorXd& a) const override;

  /// Zero when every centre of mass is level with the base joint.
  double potentialEnergy(const Eigen::VectorXd& q) const override;
  /// In the x-y plane, y up: joint i turns about z at the end of link i - 1,
  /// and at q = 0 every link hangs down (-y), as the ODE world builds it.
  RobotGeometry geometry() const override;
  /// sum_i l_i (sin phi_i, -cos phi_i, 0), phi the absolute angles.
  Eigen::Vector3d tipPosition(const Eigen::VectorXd& q) const override;

 private:
  Eigen::VectorXd absoluteAngles(const Eigen::VectorXd& q) const;
  /// L^T f: generalised forces in absolute angles to joint torques (suffix sums).
  static Eigen::VectorXd jointTorques(const Eigen::ArrayXd& absolute);

  ChainParams params_;
  Eigen::MatrixXd h_;  ///< h_ab = sum_i m_i c_ia c_ib
  Eigen::VectorXd s_;  ///< s_a = sum_i m_i c_ia
};

}  // namespace lagrange::model
