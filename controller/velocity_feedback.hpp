#pragma once
/// @file
/// Baselines 1 and 2 of docs/baselines.md: the tracking controllers that
/// measure the joint velocity q' (a tachometer: PLANT_RATE, sensors.velocity).
///
/// PD+ (B. Paden, R. Panja, Int. J. Control 47(6), 1988):
///   u = D(q) q_d'' + C(q, q') q_d' + g(q) - Kp q~ - Kd (q' - q_d').
///
/// Slotine-Li (J.-J. Slotine, W. Li, Int. J. Robotics Research 6(3), 1987):
///   q_r' = q_d' - Lambda q~,  q_r'' = q_d'' - Lambda (q' - q_d'),  s = q' - q_r',
///   u = D(q) q_r'' + C(q, q') q_r' + g(q) - KD s.
/// (Their paper's adaptive law is left out: the model is known exactly here,
/// so this is its non-adaptive form, the one the baselines table gives.)
///
/// Both are static laws of the sample (t_k, q_k, q'_k), every reference term
/// at t_k, held over the period (zero-order hold): there is nothing to
/// discretise. q~ = q - q_d. Pure: no I/O, no clock.

#include <Eigen/Dense>

#include "controller/theorem1.hpp"
#include "model/reference.hpp"
#include "model/robot_model.hpp"

namespace lagrange::controller {

/// The PD+ law at one sample, with v standing for q' (measured, or a stand-in
/// such as a backward difference: PdPlusDifferenced). `theta` carries v.
Theorem1Output pdPlusLaw(const model::RobotModel& model, const model::ReferenceSample& r,
                         const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& kp,
                         const Eigen::VectorXd& kd);

class PdPlus {
 public:
  /// @throws std::invalid_argument unless kp and kd have model.dof() positive entries.
  PdPlus(const model::RobotModel& model, const model::Reference& reference, Eigen::VectorXd kp,
         Eigen::VectorXd kd);
  /// The command at t from the measured q and q'. `theta` carries q'.
  Theorem1Output step(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot) const;
  void reset() {}

 private:
  const model::RobotModel& model_;
  const model::Reference& reference_;
  const Eigen::VectorXd kp_, kd_;
};

class SlotineLi {
 public:
  /// @throws std::invalid_argument unless lambda and kd have model.dof() positive entries.
  SlotineLi(const model::RobotModel& model, const model::Reference& reference, Eigen::VectorXd lambda,
            Eigen::VectorXd kd);
  /// The command at t from the measured q and q'. `theta` carries q',
  /// `filter_state` the sliding variable s = q' - q_r'.
  Theorem1Output step(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot) const;
  void reset() {}

 private:
  const model::RobotModel& model_;
  const model::Reference& reference_;
  const Eigen::VectorXd lambda_, kd_;
};

}  // namespace lagrange::controller
