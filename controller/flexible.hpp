#pragma once
/// @file
/// The flexible-joint controller of Corollary 3, eq. (83): the cascaded
/// controller (66) with m = 2 on xi_1 = K q2, xi_2 = K q2', its xi_1* from
/// eq. (83c) -- the Theorem 4 law on the link model whose g is g(q1) + K q1
/// (model::JointSprings) -- and the motor torque
///   tau = K (q2 - q1) + J K^-1 u          (830a),
/// which makes xi_2' = K q2'' = u exactly on the plant (595).
///
/// q2' is either measured (a motor rate sensor) or, as the paper leaves open,
/// estimated by the dirty derivative a s / (s + a) of q2, discretised exactly
/// and started bumpless (estimate 0 at t = 0). Pure: no I/O.

#include <Eigen/Dense>
#include <optional>

#include "controller/cascaded.hpp"
#include "controller/dirty_derivative.hpp"
#include "model/flexible_joint.hpp"

namespace lagrange::controller {

class FlexibleController {
 public:
  /// @param link_model the links with their springs K (model::JointSprings; see file comment).
  /// @param rate_pole empty: q2' is measured; else the dirty derivative's pole a [1/s].
  /// @param rate_filter_start filtered q2' only: the estimate filter's state at the
  ///        first sample (empty: bumpless, the estimate starts at 0).
  /// @throws std::invalid_argument unless gains.stages has 2 stages and sizes match.
  FlexibleController(const model::RobotModel& link_model, const model::Reference& reference,
                     CascadedGains gains, std::optional<Eigen::VectorXd> qc0, model::FlexibleParams params,
                     std::optional<Eigen::VectorXd> rate_pole, const std::vector<StageStart>& starts = {},
                     std::optional<Eigen::VectorXd> rate_filter_start = std::nullopt);

  struct Output {
    CascadedController::Output cascade;
    Eigen::VectorXd tau;         ///< motor torque (830a) [N m]
    Eigen::VectorXd motor_rate;  ///< the q2' used (measured or estimated) [rad/s]
  };

  /// At time t from the link angles q1, motor angles q2 and, when measured, q2'.
  /// @throws std::invalid_argument when q2' is measured but not given.
  Output step(double t, const Eigen::VectorXd& q1, const Eigen::VectorXd& q2,
              const std::optional<Eigen::VectorXd>& q2dot);
  const CascadedController& cascade() const { return cascade_; }
  /// Filtered q2' only: the estimate filter's state (after the last step's advance).
  const std::optional<DirtyDerivativeFilter>& rateFilter() const { return rate_filter_; }

 private:
  CascadedController cascade_;
  model::FlexibleParams params_;
  std::optional<DirtyDerivativeFilter> rate_filter_;
  bool rate_filter_bumpless_ = true;
  Eigen::VectorXd rate_pole_;
  bool has_previous_ = false;
  double previous_time_ = 0.0;
  Eigen::VectorXd previous_q2_;
};

}  // namespace lagrange::controller
