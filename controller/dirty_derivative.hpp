#pragma once
/// @file
/// The dirty-derivative filter of eq. (90a-b), discretised exactly for a
/// zero-order-held input:
///   qc' = -a (qc + b x),  theta = qc + b x   (theta = b s / (s + a) x)
/// Over a step T with x held constant:
///   qc[k+1] = e^{-aT} qc[k] - b (1 - e^{-aT}) x[k].
/// Forward Euler would be wrong here: aT is often near 1.

#include <Eigen/Dense>

namespace lagrange::controller {

class DirtyDerivativeFilter {
 public:
  /// a, b: per-channel positive gains; state: initial qc.
  DirtyDerivativeFilter(Eigen::VectorXd a, Eigen::VectorXd b, Eigen::VectorXd state);

  /// theta = qc + b x for the current state.
  Eigen::VectorXd output(const Eigen::VectorXd& x) const;

  /// Advance qc by dt > 0 with x held constant over the step.
  void advance(const Eigen::VectorXd& x, double dt);

  const Eigen::VectorXd& state() const { return state_; }
  void reset(Eigen::VectorXd state) { state_ = std::move(state); }

 private:
  Eigen::VectorXd a_, b_, state_;
};

}  // namespace lagrange::controller
