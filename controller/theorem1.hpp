#pragma once
/// @file
/// The position-feedback tracking controller of Theorem 4, eq. (13):
///   qc'   = -a (qc + b q~),       q~ = q - q_d(t)
///   theta = qc + b q~
///   u     = -kp q~ - kd theta + D(q) q_d'' + C(q, q_d') q_d' + g(q)
/// Gains are per joint (diagonal matrices, the paper's Remark 2). The only measurement is q.
/// Pure: no I/O, no clock; the caller supplies time.

#include <Eigen/Dense>
#include <optional>

#include "controller/dirty_derivative.hpp"
#include "controller/paper_gains.hpp"
#include "model/reference.hpp"
#include "model/robot_model.hpp"

namespace lagrange::controller {

/// What one step computed (everything the command message reports).
struct Theorem1Output {
  Eigen::VectorXd u;             ///< control input [N m]
  Eigen::VectorXd q_desired;     ///< q_d(t) [rad]
  Eigen::VectorXd q_error;       ///< q~ [rad]
  Eigen::VectorXd theta;         ///< filter output
  Eigen::VectorXd filter_state;  ///< qc used for this output (before the update)
  /// Cascaded controller only: xit_i = xi_i - xi_i*, m x n (empty otherwise).
  Eigen::MatrixXd xi_error;
};

class Theorem1Controller {
 public:
  /// initial_filter_state: qc(0); empty for a bumpless start, qc(0) = -b q~(t0)
  /// at the first step, so theta(t0) = 0 and the first command has no
  /// damping kick from a filter that has not seen the error yet.
  /// @throws std::invalid_argument on size mismatch or non-positive gains.
  Theorem1Controller(const model::RobotModel& chain, const model::Reference& reference, Theorem1Gains gains,
                     std::optional<Eigen::VectorXd> initial_filter_state);

  /// u at time t from the measured q. Before computing it, the filter is
  /// advanced from the previous measurement's time to t with the previous q~
  /// held (zero-order hold), so a missed sample costs accuracy, not
  /// correctness. @throws std::invalid_argument if t does not increase or q
  /// has the wrong size.
  Theorem1Output step(double t, const Eigen::VectorXd& q);

  /// The control law alone, eq. (90c), for a reference sample and a given
  /// theta (no state change).
  Eigen::VectorXd law(const model::ReferenceSample& ref, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& theta) const;

  const Eigen::VectorXd& filterState() const { return filter_.state(); }
  const Theorem1Gains& gains() const { return gains_; }

 private:
  const model::RobotModel& chain_;
  const model::Reference& reference_;
  Theorem1Gains gains_;
  DirtyDerivativeFilter filter_;
  bool bumpless_;
  bool has_previous_ = false;
  double previous_time_ = 0.0;
  Eigen::VectorXd previous_error_;
};

}  // namespace lagrange::controller
