#pragma once
/// @file
/// The robot-model seam: the rigid arm of eq. (10),
///   D(q) q'' + C(q, q') q' + g(q) = u,
/// as every consumer sees it -- the controllers, the bounds k_c and k_delta,
/// the chain conditions, free-motion references, the flexible-joint model, the
/// gain reports and suggestions, the sampled-data check. A robot kind (the
/// planar chain of model/planar_chain.hpp; a URDF arm through a dynamics
/// library) is one implementation; nothing above model/ names a kind except the
/// one place that builds it from the scenario (config::Scenario::robotModel).
///
/// Contract: a model is constant once built (Pinocchio's Model). Every member
/// is const, pure and safe to call from several threads at once; a kind that
/// needs scratch space (a dynamics library's solver) keeps it per call, not in
/// the object. C is the Christoffel-symbol matrix, so D' - 2C is skew-symmetric
/// and C(q, x) y = C(q, y) x (the properties the paper's proofs use); the unit
/// tests check both for every kind.

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/robot_geometry.hpp"

namespace lagrange::model {

/// One term of a closed form of C: C_k(q) = sum over terms of
/// sin(phi_a - phi_b) per_velocity[k], per_velocity[k] constant. A kind with
/// such a form (the planar chain, a and b its absolute link angles) gives
/// model/bounds.hpp a proven k_c.
struct CoriolisTerm {
  int a = 0, b = 0;
  std::vector<Eigen::MatrixXd> per_velocity;
};

class RobotModel {
 public:
  virtual ~RobotModel() = default;

  /// The robot kind, as a scenario names it ("planar_chain").
  virtual std::string kind() const = 0;
  /// n, the number of joints.
  virtual int dof() const = 0;
  /// The joints' names, base to tip (as a URDF names them; "joint1".. for the planar chain).
  virtual std::vector<std::string> jointNames() const = 0;

  /// Inertia matrix D(q), n x n, symmetric positive definite.
  virtual Eigen::MatrixXd inertia(const Eigen::VectorXd& q) const = 0;
  /// The matrices C_k(q) with C(q, v) = sum_k v_k C_k(q).
  virtual std::vector<Eigen::MatrixXd> coriolisPerVelocity(const Eigen::VectorXd& q) const = 0;
  /// C(q, v).
  virtual Eigen::MatrixXd coriolis(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  /// The product C(q, v) w, which a kind may compute without forming C.
  virtual Eigen::VectorXd coriolisTimes(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                        const Eigen::VectorXd& w) const;
  /// Gravity vector g(q) = dU/dq [N m].
  virtual Eigen::VectorXd gravity(const Eigen::VectorXd& q) const = 0;
  /// Potential energy U(q) [J]; its zero is the kind's to choose.
  virtual double potentialEnergy(const Eigen::VectorXd& q) const = 0;

  /// Inverse dynamics D(q) a + C(q, v) v + g(q) [N m]. The default forms D
  /// and C; a kind overrides it with its O(n) or O(n^2) algorithm (the planar
  /// chain's closed form, the URDF arm's recursive Newton-Euler), which the
  /// controllers' feedforward and the forward dynamics then use.
  virtual Eigen::VectorXd inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                          const Eigen::VectorXd& a) const;
  /// base + inverseDynamics(q, v, a): a control law's feedback plus its
  /// feedforward, as the controllers compute it every tick.
  Eigen::VectorXd plusInverseDynamics(const Eigen::VectorXd& base, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& v, const Eigen::VectorXd& a) const;
  /// Forward dynamics q'' = D(q)^-1 (u - C(q, v) v - g(q)), the bias terms
  /// from inverseDynamics(q, v, 0).
  virtual Eigen::VectorXd acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                       const Eigen::VectorXd& u) const;
  /// Kinetic energy v^T D(q) v / 2 [J].
  double kineticEnergy(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

  /// The arm's frames and shapes for a viewer (model/robot_geometry.hpp).
  virtual RobotGeometry geometry() const = 0;
  /// Forward kinematics of the tip point [m], in the base frame: computed by
  /// the kind itself (closed form, or its dynamics library), not from
  /// geometry(), so the one checks the other.
  virtual Eigen::Vector3d tipPosition(const Eigen::VectorXd& q) const = 0;

  /// A closed form of C for a proven k_c (model::coriolisBound); none by
  /// default, and then k_c is only estimated.
  virtual std::optional<std::vector<CoriolisTerm>> coriolisTerms() const { return std::nullopt; }

 protected:
  /// @throws std::invalid_argument unless x has dof() entries.
  void checkSize(const Eigen::VectorXd& x, const char* what) const;
};

/// Models are built once and shared by the objects that use them.
using RobotModelPtr = std::shared_ptr<const RobotModel>;

}  // namespace lagrange::model
