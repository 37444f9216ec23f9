#include "model/definiteness.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "model/spectra.hpp"

namespace lagrange::model {

double scaledMinEigenvalue(const Eigen::MatrixXd& symmetric, const Eigen::MatrixXd& scale) {
  Eigen::VectorXd d(symmetric.rows());
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    const double s = std::abs(scale(i, i));
    d(i) = s > 0.0 ? 1.0 / std::sqrt(s) : 1.0;
  }
  const Eigen::MatrixXd scaled = d.asDiagonal() * symmetric * d.asDiagonal();
  return symmetricEigenvalues(0.5 * (scaled + scaled.transpose())).minCoeff();
}

Eigen::VectorXcd balancedEigenvalues(const Eigen::MatrixXd& a) {
  Eigen::MatrixXd b = a;
  const Eigen::Index n = b.rows();
  bool changed = true;
  for (int sweep = 0; changed && sweep < 200; ++sweep) {
    changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      double column = 0.0, row = 0.0;
      for (Eigen::Index k = 0; k < n; ++k)
        if (k != i) column += std::abs(b(k, i)), row += std::abs(b(i, k));
      if (column == 0.0 || row == 0.0) continue;
      const double sum = column + row;
      double f = 1.0;
      while (column < row / 2.0) column *= 2.0, row /= 2.0, f *= 2.0;
      while (column >= row * 2.0) column /= 2.0, row *= 2.0, f /= 2.0;
      if ((column + row) < 0.95 * sum) {
        changed = true;
        b.row(i) /= f;
        b.col(i) *= f;
      }
    }
  }
  return Eigen::EigenSolver<Eigen::MatrixXd>(b, false).eigenvalues();
}

double hurwitzMargin(const Eigen::MatrixXd& a) {
  if (!a.allFinite()) return -std::numeric_limits<double>::infinity();  // nothing to decide on
  return -balancedEigenvalues(a).real().maxCoeff();
}

}  // namespace lagrange::model
