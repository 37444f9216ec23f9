#pragma once
/// @file
/// The matrix decompositions the checks need, each instantiated in this one
/// file (spectra.cpp): an Eigen decomposition costs 10-17 s of compile time in
/// every file that instantiates one, so the rest of the code, tests included,
/// calls these functions instead (docs/development.md, "Building").

#include <Eigen/Core>

namespace lagrange::model {

/// The eigenvalues of a symmetric matrix, ascending; only its lower triangle
/// is read. The same values, bit for bit, as
/// Eigen::SelfAdjointEigenSolver<MatrixXd>(m).eigenvalues() and as
/// m.selfadjointView<Eigen::Lower>().eigenvalues() (eigenvectors are not
/// computed: the eigenvalues do not depend on it).
Eigen::VectorXd symmetricEigenvalues(const Eigen::MatrixXd& symmetric);

/// The largest singular value (the spectral norm) of a non-empty matrix:
/// Eigen::JacobiSVD<MatrixXd>(m).singularValues()(0).
double largestSingularValue(const Eigen::MatrixXd& m);

}  // namespace lagrange::model
