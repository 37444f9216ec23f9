#include "model/spectra.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace lagrange::model {

Eigen::VectorXd symmetricEigenvalues(const Eigen::MatrixXd& symmetric) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(symmetric, Eigen::EigenvaluesOnly).eigenvalues();
}

double largestSingularValue(const Eigen::MatrixXd& m) {
  return Eigen::JacobiSVD<Eigen::MatrixXd>(m).singularValues()(0);
}

}  // namespace lagrange::model
