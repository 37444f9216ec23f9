#pragma once
/// @file
/// The cascaded approximate-differentiator controller of eqs. (602), (48)
/// and (66) for an arm driven through m integrators (eq. (39)), m >= 1:
///
///   xi_1*     = Theorem 4 law (eq. 610a = 90c with kp0, kd0, theta_0)
///   for i = 1..m:
///     xit_i     = xi_i - xi_i*                      (xi_i measured)
///     theta_i   = qc_i + b_i xi_i* + zeta_i
///     qc_i'     = -a_i theta_i
///     zeta_i'   = -(kd_i - sigma_i) xit_i,          sigma_1 = 0, sigma_i = b_i kp_{i-1}
///     xi_{i+1}* = -kp_i xit_i + kd_i theta_i
///   u = xi_{m+1}*
///
/// No velocity and no derivative of xi* is computed from measurements.
/// Between samples xi_i* and xit_i are held (zero-order hold); the filter
/// states are then advanced exactly: zeta_i ramps linearly and qc_i follows
/// the first-order filter driven by that ramp (closed form in advance()).
/// Pure: no I/O, no clock. Gains are per joint (diagonal), all positive.

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "controller/paper_gains.hpp"
#include "controller/theorem1.hpp"

namespace lagrange::controller {

struct CascadedGains {
  Theorem1Gains stage0;            ///< kp0, kd0, a0, b0 of eq. (48) and filter (602)
  std::vector<StageGains> stages;  ///< i = 1..m
};

/// The cascade's own states, row i-1 for stage i (m x n each).
struct CascadeState {
  Eigen::MatrixXd qc, zeta;
};

/// Everything the cascade computes from one sample.
struct CascadeSignals {
  Eigen::MatrixXd xi_star;   ///< m x n: xi_1* .. xi_m*
  Eigen::MatrixXd xi_error;  ///< m x n: xit_i = xi_i - xi_i*
  Eigen::MatrixXd theta;     ///< m x n: theta_1 .. theta_m
  Eigen::VectorXd u;         ///< xi_{m+1}*: the input of the last integrator
};

/// sigma_i of eq. (750d) for stage i (1-based), per joint.
Eigen::VectorXd cascadeSigma(const CascadedGains& gains, int stage);

/// The algebraic part of eq. (66): signals from xi_1*, the measured xi
/// (m x n) and the cascade state. No state change.
CascadeSignals evaluateCascade(const CascadedGains& gains, const Eigen::VectorXd& xi1_star,
                               const Eigen::MatrixXd& xi, const CascadeState& state);

/// Continuous-time derivative of the cascade state, eqs. (750c, 750d).
CascadeState cascadeDerivative(const CascadedGains& gains, const CascadeSignals& signals);

/// Exact advance of the cascade state by dt with the signals held.
void advanceCascade(const CascadedGains& gains, const CascadeSignals& held, double dt, CascadeState& state);

class CascadedController {
 public:
  /// qc0: stage-0 filter state (empty: bumpless); starts: per stage i = 1..m
  /// (empty: every stage at qc = zeta = 0).
  /// @throws std::invalid_argument on sizes, m < 1, non-positive gains or a
  ///         starts list that does not have m entries.
  CascadedController(const model::RobotModel& chain, const model::Reference& reference, CascadedGains gains,
                     std::optional<Eigen::VectorXd> qc0, const std::vector<StageStart>& starts = {});

  struct Output {
    Theorem1Output stage0;  ///< xi_1* is stage0.u
    CascadeSignals cascade;
  };

  /// u at time t from the measured q and actuator states xi (m x n). The
  /// filters are first advanced from the previous sample's time to t.
  Output step(double t, const Eigen::VectorXd& q, const Eigen::MatrixXd& xi);

  int order() const { return static_cast<int>(gains_.stages.size()); }
  const CascadeState& state() const { return state_; }
  const Theorem1Controller& stage0() const { return stage0_; }

 private:
  CascadedGains gains_;
  Theorem1Controller stage0_;
  CascadeState state_;
  std::vector<bool> bumpless_;  ///< per stage, consumed at the first step
  std::optional<CascadeSignals> held_;
  double held_time_ = 0.0;
};

}  // namespace lagrange::controller
