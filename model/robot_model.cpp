#include "model/robot_model.hpp"

#include <stdexcept>

namespace lagrange::model {

Eigen::MatrixXd RobotModel::coriolis(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  checkSize(v, "v");
  const std::vector<Eigen::MatrixXd> ck = coriolisPerVelocity(q);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(dof(), dof());
  for (int k = 0; k < dof(); ++k) c += v(k) * ck[k];
  return c;
}

Eigen::VectorXd RobotModel::coriolisTimes(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                          const Eigen::VectorXd& w) const {
  return coriolis(q, v) * w;
}

Eigen::VectorXd RobotModel::inverseDynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                            const Eigen::VectorXd& a) const {
  return inertia(q) * a + coriolis(q, v) * v + gravity(q);
}

Eigen::VectorXd RobotModel::plusInverseDynamics(const Eigen::VectorXd& base, const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& v, const Eigen::VectorXd& a) const {
  return base + inverseDynamics(q, v, a);
}

Eigen::VectorXd RobotModel::acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                         const Eigen::VectorXd& u) const {
  checkSize(u, "u");
  const Eigen::VectorXd rhs = u - inverseDynamics(q, v, Eigen::VectorXd::Zero(dof()));
  return inertia(q).llt().solve(rhs);
}

double RobotModel::kineticEnergy(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  checkSize(v, "v");
  return 0.5 * v.dot(inertia(q) * v);
}

void RobotModel::checkSize(const Eigen::VectorXd& x, const char* what) const {
  if (x.size() != dof())
    throw std::invalid_argument(kind() + " model: " + what + " has " + std::to_string(x.size()) +
                                " entries, expected " + std::to_string(dof()));
}

}  // namespace lagrange::model
