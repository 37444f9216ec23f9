#pragma once
/// @file
/// An arm with torsional springs from each joint to its zero angle: K q added
/// to g(q) and q^T K q / 2 to the potential energy, D and C unchanged. Not a
/// plant part: this is how the flexible-joint model (595) looks from its links
/// once written as the chain (600) (Example 1: g(q1) + K q1; eqs. 608, 830c).
/// It wraps any robot kind, so every kind gets its flexible-joint version.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "model/robot_model.hpp"

namespace lagrange::model {

class JointSprings : public RobotModel {
 public:
  /// @throws std::invalid_argument unless `links` is set and `stiffness` has
  ///         links->dof() positive finite entries [N m / rad].
  JointSprings(RobotModelPtr links, Eigen::VectorXd stiffness);

  /// The wrapped kind's: the springs change the arm's potential, not its kind.
  std::string kind() const override { return links_->kind(); }
  int dof() const override { return links_->dof(); }
  std::vector<std::string> jointNames() const override { return links_->jointNames(); }
  const Eigen::VectorXd& stiffness() const { return stiffness_; }

  Eigen::MatrixXd inertia(const Eigen::VectorXd& q) const override { return links_->inertia(q); }
  std::vector<Eigen::MatrixXd> coriolisPerVelocity(const Eigen::VectorXd& q) const override {
    return links_->coriolisPerVelocity(q);
  }
  Eigen::MatrixXd coriolis(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const override {
    return links_->coriolis(q, v);
  }
  Eigen::VectorXd coriolisTimes(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& w) const override {
    return links_->coriolisTimes(q, v, w);
  }
  std::optional<std::vector<CoriolisTerm>> coriolisTerms() const override { return links_->coriolisTerms(); }
  RobotGeometry geometry() const override { return links_->geometry(); }
  Eigen::Vector3d tipPosition(const Eigen::VectorXd& q) const override { return links_->tipPosition(q); }

  /// g(q) + K q.
  Eigen::VectorXd gravity(const Eigen::VectorXd& q) const override;
  /// The arm's inverse dynamics + K q.
  Eigen::VectorXd inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  const Eigen::VectorXd& a) const override;
  /// U(q) + q^T K q / 2.
  double potentialEnergy(const Eigen::VectorXd& q) const override;

 private:
  RobotModelPtr links_;
  Eigen::VectorXd stiffness_;
};

}  // namespace lagrange::model
