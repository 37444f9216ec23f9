#pragma once
/// @file
/// Baseline 3 of docs/baselines.md: PD+ (Paden and Panja, Int. J. Control
/// 47(6), 1988) with the measured velocity replaced by the backward difference
/// of the sampled positions -- what practitioners run when only encoders are
/// fitted:
///
///   v_k = (q_k - q_{k-1}) / (t_k - t_{k-1}),
///   u_k = D(q_k) q_d'' + C(q_k, v_k) q_d' + g(q_k) - Kp q~_k - Kd (v_k - q_d'),
///
/// q~ = q - q_d, every reference term at t_k. At the first sample there is no
/// previous position: v_0 = q_d'(t_0), so the first command carries no damping
/// kick (the analogue of Theorem 4's bumpless filter start). PD+ with the true
/// velocity tracks globally; with the difference there is no guarantee, and
/// noise on q reaches u multiplied by Kd / T. Pure: no I/O, no clock.

#include <Eigen/Dense>
#include <optional>

#include "controller/theorem1.hpp"
#include "model/reference.hpp"
#include "model/robot_model.hpp"

namespace lagrange::controller {

class PdPlusDifferenced {
 public:
  /// @throws std::invalid_argument unless kp and kd have model.dof() positive entries.
  PdPlusDifferenced(const model::RobotModel& model, const model::Reference& reference, Eigen::VectorXd kp,
                    Eigen::VectorXd kd);

  /// The command at t from the position sampled at t; t increases from call to call.
  /// `theta` carries the differenced velocity v_k (the diagnostic slot of a rate estimate).
  Theorem1Output step(double t, const Eigen::VectorXd& q);
  void reset() { previous_.reset(); }

 private:
  struct Sample {
    double t;
    Eigen::VectorXd q;
  };
  const model::RobotModel& model_;
  const model::Reference& reference_;
  const Eigen::VectorXd kp_, kd_;
  std::optional<Sample> previous_;
};

}  // namespace lagrange::controller
