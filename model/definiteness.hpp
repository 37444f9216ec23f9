#pragma once
/// @file
/// Sign tests for matrices whose entries span tens of decades, as the
/// constructive gains of Proposition 1 produce (k_p2 ~ 1e33 next to k_p1 ~ 1e11).
/// A plain eigen-decomposition of such a matrix is accurate only to ~1e-16 of
/// its largest entry, which swamps the small eigenvalues whose sign is the
/// question. Both helpers first rescale so that every entry is O(1).

#include <Eigen/Dense>

namespace lagrange::model {

/// The smallest eigenvalue of the congruence D M D of the symmetric matrix M,
/// D = diag(|scale_ii|)^(-1/2) (scale_ii = 0 counts as 1). By Sylvester's law of
/// inertia it has the sign of lambda_min(M); with scale = M it is the
/// eigenvalue of the unit-diagonal (Jacobi-scaled) form of M, so
/// "M - c diag(M) >= 0" reads "result >= 1 - c".
double scaledMinEigenvalue(const Eigen::MatrixXd& symmetric, const Eigen::MatrixXd& scale);

/// -max Re eig(A) after a diagonal similarity that balances A's row and
/// column norms (Parlett-Reinsch, powers of two: exact in floating point).
/// Positive when A is Hurwitz; -infinity when A has a non-finite entry.
double hurwitzMargin(const Eigen::MatrixXd& a);

/// The eigenvalues of a (finite) after balancing it by a diagonal similarity
/// (powers of two, Parlett-Reinsch), which leaves them unchanged in exact
/// arithmetic and keeps rows and columns of very different scales from
/// swamping the small ones in rounding.
Eigen::VectorXcd balancedEigenvalues(const Eigen::MatrixXd& a);

}  // namespace lagrange::model
