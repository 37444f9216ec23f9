#pragma once
// What every robot kind must satisfy (model/robot_model.hpp), checked at one
// random state: a new kind's test calls this on its own models.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "model/robot_model.hpp"
#include "model/spectra.hpp"

namespace lagrange::testing {

inline Eigen::VectorXd randomVector(std::mt19937_64& rng, int n, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = u(rng);
  return v;
}

inline void expectRobotModelProperties(const model::RobotModel& arm, std::mt19937_64& rng) {
  const int n = arm.dof();
  ASSERT_EQ(static_cast<int>(arm.jointNames().size()), n);
  const Eigen::VectorXd q = randomVector(rng, n, 10.0), v = randomVector(rng, n, 5.0),
                        z = randomVector(rng, n, 5.0);
  const Eigen::MatrixXd d = arm.inertia(q);
  // D symmetric positive definite.
  EXPECT_LT((d - d.transpose()).norm(), 1e-12);
  EXPECT_GT(lagrange::model::symmetricEigenvalues(d).minCoeff(), 0.0);
  // D' - 2C skew-symmetric, with D' = sum_k dD/dq_k v_k from a central difference.
  const double h = 1e-6;
  const Eigen::MatrixXd d_dot = (arm.inertia(q + h * v) - arm.inertia(q - h * v)) / (2 * h);
  const Eigen::MatrixXd n_mat = d_dot - 2 * arm.coriolis(q, v);
  EXPECT_LT((n_mat + n_mat.transpose()).norm(), 1e-6 * (1 + d_dot.norm()));
  // C(q, x) y = C(q, y) x, and the product agrees with the matrix.
  EXPECT_LT((arm.coriolis(q, v) * z - arm.coriolis(q, z) * v).norm(), 1e-10 * (1 + d.norm()));
  EXPECT_LT((arm.coriolisTimes(q, v, z) - arm.coriolis(q, v) * z).norm(), 1e-12 * (1 + d.norm()));
  // g = dU/dq.
  Eigen::VectorXd grad(n);
  for (int k = 0; k < n; ++k) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, k) * h;
    grad(k) = (arm.potentialEnergy(q + e) - arm.potentialEnergy(q - e)) / (2 * h);
  }
  EXPECT_LT((grad - arm.gravity(q)).norm(), 1e-6 * (1 + grad.norm()));
  // The kind's inverse dynamics is D a + C(q, v) v + g (a kind's own
  // algorithm against the matrices), and the controllers' sum adds it.
  const Eigen::VectorXd a = randomVector(rng, n, 5.0), base = randomVector(rng, n, 5.0);
  const Eigen::VectorXd by_matrices = d * a + arm.coriolis(q, v) * v + arm.gravity(q);
  EXPECT_LT((arm.inverseDynamics(q, v, a) - by_matrices).norm(), 1e-10 * (1 + by_matrices.norm()));
  EXPECT_EQ(arm.plusInverseDynamics(base, q, v, a), base + arm.inverseDynamics(q, v, a));
  // Forward and inverse dynamics invert each other; kinetic energy is v^T D v / 2.
  const Eigen::VectorXd u = randomVector(rng, n, 20.0);
  EXPECT_LT((arm.inverseDynamics(q, v, arm.acceleration(q, v, u)) - u).norm(), 1e-9 * (1 + u.norm()));
  EXPECT_NEAR(arm.kineticEnergy(q, v), 0.5 * v.dot(d * v), 1e-12 * (1 + v.dot(d * v)));
  // Wrong sizes are refused, naming the kind.
  EXPECT_THROW(arm.inertia(Eigen::VectorXd::Zero(n + 1)), std::invalid_argument);
}

}  // namespace lagrange::testing
