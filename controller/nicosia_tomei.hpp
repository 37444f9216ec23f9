#pragma once
/// @file
/// Baseline 4 of docs/baselines.md: S. Nicosia and P. Tomei, "Robot control by
/// using only joint position measurements", IEEE TAC 35(9), 1990 -- PD+ on the
/// velocity estimate of a model-based observer:
///
///   qh' = zh + Ld (q - qh),
///   zh' = D(q)^-1 (u - C(q, qh') qh' - g(q)) + Lp (q - qh),
///   u   = D(q) q_d'' + C(q, qh') q_d' + g(q) - Kp q~ - Kd (qh' - q_d'),
///
/// qh' = zh + Ld (q - qh) the estimate of q'. Discretisation (the observer is
/// nonlinear): at each sample the law from the measured q_k and the observer's
/// state; then the observer integrated over the period by RK4, in sub-steps
/// short enough that every gain times the sub-step is at most 0.5, with u_k
/// held (as the plant sees it) and the innovation q_k - qh(t_k) held -- taken
/// where q is known, at the sample. Holding q_k instead and letting qh run on
/// within the period biases the correction by about Lp q' T / 2: on the
/// Pelican at 1 kHz that left a 5.4 mrad tracking residual, first order in T;
/// the held innovation leaves 0.03 mrad (tests/unit/baselines_test.cpp). Start: qh(t0) = q(t0),
/// zh(t0) = 0 (the observer knows nothing of the initial velocity). The paper
/// claims local tracking. Pure: no I/O, no clock.

#include <Eigen/Dense>
#include <optional>

#include "controller/theorem1.hpp"
#include "model/reference.hpp"
#include "model/robot_model.hpp"

namespace lagrange::controller {

struct NicosiaTomeiGains {
  Eigen::VectorXd kp;  ///< [N m / rad]
  Eigen::VectorXd kd;  ///< on the estimated velocity error [N m s / rad]
  Eigen::VectorXd lp;  ///< observer gain on q - qh in zh' [1/s^2]
  Eigen::VectorXd ld;  ///< observer gain on q - qh in qh' [1/s]
};

class NicosiaTomei {
 public:
  /// @throws std::invalid_argument unless every gain has model.dof() positive entries.
  NicosiaTomei(const model::RobotModel& model, const model::Reference& reference, NicosiaTomeiGains gains);

  /// The command at t from the position sampled at t; t increases from call
  /// to call. `theta` carries the velocity estimate qh', `filter_state` qh.
  Theorem1Output step(double t, const Eigen::VectorXd& q);
  void reset() { state_.reset(); }

 private:
  struct State {
    double t;
    Eigen::VectorXd q, u;  ///< the sample and the command held over the period that follows
    Eigen::VectorXd qh, zh;
  };
  /// (qh', zh') at zh with q, u and the innovation e held (qh enters through e only).
  std::pair<Eigen::VectorXd, Eigen::VectorXd> derivative(const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                                                         const Eigen::VectorXd& zh,
                                                         const Eigen::VectorXd& e) const;
  void advance(State& s, double t) const;

  const model::RobotModel& model_;
  const model::Reference& reference_;
  const NicosiaTomeiGains gains_;
  std::optional<State> state_;
};

}  // namespace lagrange::controller
