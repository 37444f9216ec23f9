#include "controller/cascaded.hpp"

#include <stdexcept>
#include <string>

namespace lagrange::controller {

namespace {
void requirePositive(const Eigen::VectorXd& v, const std::string& name, int n) {
  if (v.size() != n)
    throw std::invalid_argument("CascadedController: gain " + name + " has " + std::to_string(v.size()) +
                                " entries, expected " + std::to_string(n));
  if (!(v.array() > 0.0).all() || !v.allFinite())
    throw std::invalid_argument("CascadedController: gain " + name + " must be positive and finite");
}
}  // namespace

Eigen::VectorXd cascadeSigma(const CascadedGains& gains, int stage) {
  const StageGains& g = gains.stages.at(stage - 1);
  if (stage == 1) return Eigen::VectorXd::Zero(g.kp.size());
  return g.b.cwiseProduct(gains.stages.at(stage - 2).kp);
}

CascadeSignals evaluateCascade(const CascadedGains& gains, const Eigen::VectorXd& xi1_star,
                               const Eigen::MatrixXd& xi, const CascadeState& state) {
  const int m = static_cast<int>(gains.stages.size());
  const int n = static_cast<int>(xi1_star.size());
  CascadeSignals s;
  s.xi_star.resize(m, n);
  s.xi_error.resize(m, n);
  s.theta.resize(m, n);
  Eigen::VectorXd star = xi1_star;
  for (int i = 0; i < m; ++i) {
    const StageGains& g = gains.stages[i];
    s.xi_star.row(i) = star.transpose();
    const Eigen::VectorXd error = xi.row(i).transpose() - star;
    const Eigen::VectorXd theta =
        state.qc.row(i).transpose() + g.b.cwiseProduct(star) + state.zeta.row(i).transpose();
    s.xi_error.row(i) = error.transpose();
    s.theta.row(i) = theta.transpose();
    star = -g.kp.cwiseProduct(error) + g.kd.cwiseProduct(theta);  // xi_{i+1}*
  }
  s.u = star;
  return s;
}

CascadeState cascadeDerivative(const CascadedGains& gains, const CascadeSignals& s) {
  const int m = static_cast<int>(gains.stages.size());
  CascadeState d{Eigen::MatrixXd(s.theta.rows(), s.theta.cols()),
                 Eigen::MatrixXd(s.theta.rows(), s.theta.cols())};
  for (int i = 0; i < m; ++i) {
    const StageGains& g = gains.stages[i];
    d.qc.row(i) = -(g.a.cwiseProduct(s.theta.row(i).transpose())).transpose();
    d.zeta.row(i) =
        -((g.kd - cascadeSigma(gains, i + 1)).cwiseProduct(s.xi_error.row(i).transpose())).transpose();
  }
  return d;
}

void advanceCascade(const CascadedGains& gains, const CascadeSignals& held, double dt, CascadeState& state) {
  if (!(dt > 0.0)) throw std::invalid_argument("CascadedController: time must increase between steps");
  const int m = static_cast<int>(gains.stages.size());
  for (int i = 0; i < m; ++i) {
    const StageGains& g = gains.stages[i];
    // zeta' = -c (c constant over the step), qc' = -a (qc + b xi* + zeta):
    //   zeta(T) = zeta0 - c T
    //   qc(T)   = e qc0 - (1 - e)(b xi* + zeta0) + c (T - (1 - e) / a),  e = exp(-a T)
    const Eigen::ArrayXd c =
        (g.kd - cascadeSigma(gains, i + 1)).array() * held.xi_error.row(i).transpose().array();
    const Eigen::ArrayXd e = (-g.a.array() * dt).exp();
    const Eigen::ArrayXd qc0 = state.qc.row(i).transpose().array();
    const Eigen::ArrayXd zeta0 = state.zeta.row(i).transpose().array();
    const Eigen::ArrayXd w0 = g.b.array() * held.xi_star.row(i).transpose().array() + zeta0;
    state.qc.row(i) = (e * qc0 - (1.0 - e) * w0 + c * (dt - (1.0 - e) / g.a.array())).matrix().transpose();
    state.zeta.row(i) = (zeta0 - c * dt).matrix().transpose();
  }
}

CascadedController::CascadedController(const model::RobotModel& chain, const model::Reference& reference,
                                       CascadedGains gains, std::optional<Eigen::VectorXd> qc0,
                                       const std::vector<StageStart>& starts)
    : gains_(std::move(gains)), stage0_(chain, reference, gains_.stage0, std::move(qc0)) {
  const int n = chain.dof();
  const int m = static_cast<int>(gains_.stages.size());
  if (m < 1) throw std::invalid_argument("CascadedController: at least one stage (m >= 1) is needed");
  for (int i = 0; i < m; ++i) {
    const std::string stage = "stage " + std::to_string(i + 1) + " ";
    requirePositive(gains_.stages[i].kp, stage + "kp", n);
    requirePositive(gains_.stages[i].kd, stage + "kd", n);
    requirePositive(gains_.stages[i].a, stage + "a", n);
    requirePositive(gains_.stages[i].b, stage + "b", n);
  }
  state_.qc = Eigen::MatrixXd::Zero(m, n);
  state_.zeta = Eigen::MatrixXd::Zero(m, n);
  bumpless_.assign(m, false);
  if (!starts.empty() && static_cast<int>(starts.size()) != m)
    throw std::invalid_argument("CascadedController: " + std::to_string(starts.size()) +
                                " stage starts for " + std::to_string(m) + " stages");
  for (int i = 0; i < static_cast<int>(starts.size()); ++i) {
    const StageStart& st = starts[i];
    for (const Eigen::VectorXd* v : {&st.qc, &st.zeta})
      if (v->size() != 0 && (v->size() != n || !v->allFinite()))
        throw std::invalid_argument("CascadedController: stage " + std::to_string(i + 1) +
                                    " initial state must have " + std::to_string(n) + " finite entries");
    bumpless_[i] = st.bumpless;
    if (st.qc.size() != 0 && !st.bumpless) state_.qc.row(i) = st.qc.transpose();
    if (st.zeta.size() != 0) state_.zeta.row(i) = st.zeta.transpose();
  }
}

CascadedController::Output CascadedController::step(double t, const Eigen::VectorXd& q,
                                                    const Eigen::MatrixXd& xi) {
  if (xi.rows() != order() || xi.cols() != q.size())
    throw std::invalid_argument("CascadedController: actuator state must be " + std::to_string(order()) +
                                " x " + std::to_string(q.size()));
  if (held_) advanceCascade(gains_, *held_, t - held_time_, state_);
  Output out;
  out.stage0 = stage0_.step(t, q);
  if (!held_) {
    // Bumpless stages: xi_i* depends on the stages before i only, so fix
    // theta_i = 0 stage by stage, evaluating the cascade again after each.
    for (int i = 0; i < order(); ++i) {
      if (!bumpless_[i]) continue;
      const CascadeSignals before = evaluateCascade(gains_, out.stage0.u, xi, state_);
      state_.qc.row(i) = -(gains_.stages[i].b.cwiseProduct(before.xi_star.row(i).transpose())).transpose() -
                         state_.zeta.row(i);
    }
  }
  out.cascade = evaluateCascade(gains_, out.stage0.u, xi, state_);
  held_ = out.cascade;
  held_time_ = t;
  return out;
}

}  // namespace lagrange::controller
