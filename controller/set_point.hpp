#pragma once
/// @file
/// Baseline 6 of docs/baselines.md: the set-point controller of R. Kelly (IFAC
/// 1993) and H. Berghuis and H. Nijmeijer (Systems & Control Letters 21, 1993)
/// -- PD with gravity compensation whose damping acts on a dirty derivative of
/// the measured position, for a constant q_d:
///
///   u = g(q) - Kp q~ - Kd theta,   theta = b s / (s + a) q,
///
/// realised as qc' = -a (qc + b q), theta = qc + b q, the filter discretised
/// exactly with q held over each period (controller/dirty_derivative.hpp, the
/// Theorem 4 controller's). It starts bumpless, qc(t0) = -b q(t0), so
/// theta(t0) = 0. Global asymptotic regulation for every positive diagonal
/// Kp, Kd, a, b (Kelly 1993); it is not a tracking controller, and the
/// scenario must hold q_d constant. Pure: no I/O, no clock.

#include <Eigen/Dense>
#include <optional>

#include "controller/dirty_derivative.hpp"
#include "controller/theorem1.hpp"
#include "model/reference.hpp"
#include "model/robot_model.hpp"

namespace lagrange::controller {

class SetPoint {
 public:
  /// @throws std::invalid_argument unless every gain has model.dof() positive entries.
  SetPoint(const model::RobotModel& model, const model::Reference& reference, Theorem1Gains gains);

  /// The command at t from the position sampled at t; t increases from call to call.
  Theorem1Output step(double t, const Eigen::VectorXd& q);
  void reset() { previous_.reset(); }

 private:
  struct Sample {
    double t;
    Eigen::VectorXd q;
  };
  const model::RobotModel& model_;
  const model::Reference& reference_;
  const Theorem1Gains gains_;
  DirtyDerivativeFilter filter_;
  std::optional<Sample> previous_;
};

}  // namespace lagrange::controller
