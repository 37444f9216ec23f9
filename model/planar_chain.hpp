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
#include <vector>

namespace lagrange::model {

/// One link pair's share of the Coriolis matrix: for a < b (absolute link
/// indices, phi the absolute angles),
///   C_k(q) = sum over pairs of sin(phi_a - phi_b) per_velocity[k],
/// with per_velocity[k] constant (from h_ab alone).
struct CoriolisTerm {
  int a = 0, b = 0;
  std::vector<Eigen::MatrixXd> per_velocity;
};

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
  /// Torsional springs from each joint to its zero angle [N m / rad] (empty:
  /// none): they add K q to g(q) and q^T K q / 2 to the potential energy. Not a
  /// plant part: this is how the flexible-joint model (595) looks from its links
  /// once written as the chain (600) (Example 1: g(q1) + K q1).
  Eigen::VectorXd joint_stiffness;
};

/// The 2-DOF "Pelican" arm of Kelly, Santibanez and Loria, "Control of Robot
/// Manipulators in Joint Space", Springer 2005, Table 5.1.
ChainParams pelicanParams();

/// Dynamics of an n-link planar chain. Immutable after construction; every
/// function is pure and thread-safe.
class PlanarChain {
 public:
  /// @throws std::invalid_argument if there are no links, or a length,
  ///         mass or inertia is not positive, or com is negative or not finite.
  explicit PlanarChain(ChainParams params);

  int dof() const { return static_cast<int>(params_.links.size()); }
  const ChainParams& params() const { return params_; }

  /// Inertia matrix D(q), n x n, symmetric positive definite.
  Eigen::MatrixXd inertia(const Eigen::VectorXd& q) const;

  /// Partial derivatives dD/dq_k, k = 0..n-1.
  std::vector<Eigen::MatrixXd> inertiaPartials(const Eigen::VectorXd& q) const;

  /// Coriolis and centrifugal matrix C(q, v) from Christoffel symbols.
  Eigen::MatrixXd coriolis(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

  /// The matrices C_k(q) with C(q, v) = sum_k v_k C_k(q).
  std::vector<Eigen::MatrixXd> coriolisPerVelocity(const Eigen::VectorXd& q) const;

  /// The closed form of C: one term per link pair with h_ab != 0. Used for a
  /// proven bound of ||C(q, y)|| / ||y|| (model/bounds.hpp); C itself is
  /// computed by coriolisPerVelocity.
  std::vector<CoriolisTerm> coriolisTerms() const;

  /// Gravity vector g(q) = dU/dq [N m].
  Eigen::VectorXd gravity(const Eigen::VectorXd& q) const;

  /// Potential energy U(q) [J], zero when every centre of mass is level with the base joint.
  double potentialEnergy(const Eigen::VectorXd& q) const;

  /// Kinetic energy v^T D(q) v / 2 [J].
  double kineticEnergy(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

  /// Forward dynamics: q'' = D(q)^-1 (u - C(q, v) v - g(q)).
  Eigen::VectorXd acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                               const Eigen::VectorXd& u) const;

 private:
  void checkSize(const Eigen::VectorXd& x, const char* what) const;
  Eigen::VectorXd absoluteAngles(const Eigen::VectorXd& q) const;

  ChainParams params_;
  Eigen::MatrixXd h_;  ///< h_ab = sum_i m_i c_ia c_ib
  Eigen::VectorXd s_;  ///< s_a = sum_i m_i c_ia
};

}  // namespace lagrange::model
