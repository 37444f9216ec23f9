#pragma once
/// @file
/// Baseline 5 of docs/baselines.md: H. Berghuis and H. Nijmeijer, "A passivity
/// approach to controller-observer design for robots", IEEE Trans. Robotics
/// and Automation 9(6), 1993 -- a controller and a linear observer designed
/// together:
///
///   qr'  = q_d' - Lambda (qh - q_d),      q0' = qh' - Lambda (qh - q),
///   u    = D(q) qr'' + C(q, q0') qr' + g(q) - Kd (q0' - qr') - Kp q~,
///   qh'  = zh + Ld (q - qh),              zh' = qr'' + Lp (q - qh),
///
/// with qr'' = q_d'' - Lambda (qh' - q_d'). Discretisation as the Nicosia-Tomei
/// observer's (controller/nicosia_tomei.hpp): the law at each sample, then the
/// observer by RK4 over the period with the innovation q_k - qh(t_k) held and
/// the reference's terms at each RK4 stage's time, in sub-steps with every gain
/// times the sub-step at most 0.5. Start: qh(t0) = q(t0), zh(t0) = 0, as
/// Nicosia-Tomei's. The paper claims semiglobal
/// exponential tracking (the region grows with the gains). Pure: no I/O.

#include <Eigen/Dense>
#include <optional>

#include "controller/theorem1.hpp"
#include "model/reference.hpp"
#include "model/robot_model.hpp"

namespace lagrange::controller {

struct BerghuisNijmeijerGains {
  Eigen::VectorXd kp;      ///< [N m / rad]
  Eigen::VectorXd kd;      ///< [N m s / rad]
  Eigen::VectorXd lambda;  ///< Lambda [1/s]
  Eigen::VectorXd lp;      ///< observer gain on q - qh in zh' [1/s^2]
  Eigen::VectorXd ld;      ///< observer gain on q - qh in qh' [1/s]
};

class BerghuisNijmeijer {
 public:
  /// @throws std::invalid_argument unless every gain has model.dof() positive entries.
  BerghuisNijmeijer(const model::RobotModel& model, const model::Reference& reference,
                    BerghuisNijmeijerGains gains);

  /// The command at t from the position sampled at t; t increases from call
  /// to call. `theta` carries the velocity estimate qh', `filter_state` qh.
  Theorem1Output step(double t, const Eigen::VectorXd& q);
  void reset() { state_.reset(); }

 private:
  struct State {
    double t;
    Eigen::VectorXd q, qh, zh;
  };
  void advance(State& s, double t) const;

  const model::RobotModel& model_;
  const model::Reference& reference_;
  const BerghuisNijmeijerGains gains_;
  std::optional<State> state_;
};

}  // namespace lagrange::controller
