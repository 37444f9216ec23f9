#pragma once
/// @file
/// The gains and filter starts of the paper's controllers, as plain data: what
/// a scenario's controller section holds (config/scenario.hpp) and what the
/// controllers take (theorem1.hpp, cascaded.hpp, flexible.hpp). Data only, so
/// that config depends on no controller's code: a change to a control law
/// recompiles the controllers, not every file that reads a scenario.

#include <Eigen/Dense>

namespace lagrange::controller {

/// Diagonal gains of eq. (13), one entry per joint, all positive.
struct Theorem1Gains {
  Eigen::VectorXd kp;  ///< proportional [N m / rad]
  Eigen::VectorXd kd;  ///< damping on theta [N m s / rad when b = a]
  Eigen::VectorXd a;   ///< filter pole [1/s]
  Eigen::VectorXd b;   ///< filter gain [1/s]
};

/// Gains of one cascade stage i >= 1, per joint.
struct StageGains {
  Eigen::VectorXd kp, kd, a, b;
};

/// How stage i's filter starts (its qc_i(0) and zeta_i(0)), like stage 0's
/// initial_filter_state: given values (empty: zeros), or bumpless, qc_i(0) =
/// -b_i xi_i*(t0) - zeta_i(0) at the first sample, so theta_i(t0) = 0 and the
/// first command has no kick from a filter that has not seen xi_i* yet.
/// Zeros, the default, give theta_i(t0) = b_i xi_i*(t0): with xi_1* of a few
/// hundred N m that is a command kick of kd_i b_i xi_i*.
struct StageStart {
  bool bumpless = false;
  Eigen::VectorXd qc;    ///< qc_i(0) when not bumpless; empty: zeros
  Eigen::VectorXd zeta;  ///< zeta_i(0); empty: zeros
};

}  // namespace lagrange::controller
