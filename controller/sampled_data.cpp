#include "controller/sampled_data.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "actuator/integrator_chain.hpp"
#include "controller/cascaded.hpp"
#include "controller/flexible.hpp"
#include "controller/paper_section.hpp"
#include "controller/theorem1.hpp"
#include "model/definiteness.hpp"
#include "model/flexible_joint.hpp"
#include "model/spectra.hpp"

namespace lagrange::controller {

namespace {

// The closed loop's one-period map, its state packed in one vector:
// [q, q', (q2, q2'), xi (m x n, cascaded), qc0, cascade qc + zeta (s x n), (rate filter),
//  (pending torque: steps x n), (past angles: d x n)].
// With a joint-angle sensor d samples late (sensors.position.delay) the
// controller reads q(t_{k-d}): the map keeps the last d angles, newest first.
// With `one_period_delay` (the realtime wiring: the plant steps over
// [t_k, t_{k+1}] with the newest torque it has at t_k, which answered q(t_{k-1}))
// the drive's output waits one period in the pending rows; without it (lockstep,
// in-process) the torque computed from q(t_k) acts over [t_k, t_{k+1}].
class LoopMap {
 public:
  LoopMap(const config::Scenario& s, bool one_period_delay, bool sensor_delay)
      : s_(s),
        paper_(paperSettings(s)),
        control_model_(s.controlModel()),
        arm_(s.robotModel()),
        reference_(s.reference),
        n_(s.dof()),
        order_(s.actuator.order),
        stages_(static_cast<int>(paper_.stages.size())),
        flexible_(s.controller.type == "flexible"),
        filtered_rate_(flexible_ && paper_.motor_rate == MotorRate::kFiltered),
        delayed_(one_period_delay),
        seen_(sensor_delay && s.sensors ? s.sensors->position.delay : 0),
        steps_(s.torqueStepsPerTick()) {
    if (flexible_) flexible_plant_.emplace(arm_, s.flexible->params);
  }

  // The cascade's qc_i and zeta_i enter every output only through their sum
  // (theta_i = qc_i + b_i xi_i* + zeta_i), so the implementation's state is
  // not minimal: (qc_i + d, zeta_i - d) is a neutral mode no output sees. The
  // map keeps the sum in qc_i and zeta_i at zero.
  int size() const {
    return n_ * ((flexible_ ? 4 : 2) + order_ + 1 + stages_ + (filtered_rate_ ? 1 : 0) +
                 (delayed_ ? steps_ : 0) + seen_);
  }

  // The reference's state at t with every filter at rest and the drive at the feedforward.
  Eigen::VectorXd nominal(double t) const {
    const model::ReferenceSample r = reference_.evaluate(t, 2);
    const Eigen::VectorXd h = control_model_->inverseDynamics(r.q(), r.qd(), r.qdd());
    Unpacked u = zeros();
    u.q = r.q();
    u.v = r.qd();
    if (delayed_) u.pending.rowwise() = h.transpose();  // the drive at the feedforward
    u.seen.rowwise() = r.q().transpose();               // the past readings, at the reference's angle
    if (order_ > 0) u.xi.row(0) = h.transpose();
    if (stages_ > 0) u.cascade.qc.row(0) = -(paper_.stages[0].b.cwiseProduct(h)).transpose();
    if (flexible_) {
      u.q2 = h.cwiseQuotient(s_.flexible->params.stiffness);  // K q2 = xi_1* (830c)
      u.v2 = r.qd();
      if (filtered_rate_) u.rate = u.v2 - paper_.motor_rate_pole.cwiseProduct(u.q2);
    }
    return pack(u);
  }

  // x at t_k -> x at t_k + period, the torque in `torque_steps` steps.
  Eigen::VectorXd step(const Eigen::VectorXd& x, double t, double period, int torque_steps) const {
    Unpacked u = unpack(x);
    const CascadedGains gains{paper_.gains, paper_.stages};
    std::vector<StageStart> starts;
    for (int i = 0; i < stages_; ++i)
      starts.push_back({false, u.cascade.qc.row(i).transpose(), u.cascade.zeta.row(i).transpose()});
    actuator::IntegratorChain drive(n_, order_, std::nullopt, u.xi);
    Unpacked next = u;
    // The angles the controller reads at t_k and (once the plant has moved)
    // at t_k + period: q itself, or the reading d samples late.
    if (seen_ > 0) {
      next.seen.bottomRows(seen_ - 1) = u.seen.topRows(seen_ - 1);
      next.seen.row(0) = u.q.transpose();
    }
    const Eigen::VectorXd read_now = seen_ > 0 ? Eigen::VectorXd(u.seen.row(seen_ - 1).transpose()) : u.q;
    auto readNext = [&] {
      return seen_ > 0 ? Eigen::VectorXd(next.seen.row(seen_ - 1).transpose()) : next.q;
    };
    if (flexible_) {
      FlexibleController ctl(*control_model_, reference_, gains, u.qc0, s_.flexible->params,
                             filtered_rate_ ? std::optional(paper_.motor_rate_pole) : std::nullopt, starts,
                             filtered_rate_ ? std::optional(u.rate) : std::nullopt);
      const Eigen::VectorXd tau = ctl.step(t, read_now, u.q2, u.v2).tau;
      drivePlant(next, drive.step(tau, period, torque_steps).tau, period);
      ctl.step(t + period, readNext(), next.q2, next.v2);  // advances the filters over the period
      next.qc0 = ctl.cascade().stage0().filterState();
      next.cascade = ctl.cascade().state();
      if (filtered_rate_) next.rate = ctl.rateFilter()->state();
    } else if (stages_ > 0) {
      CascadedController ctl(*control_model_, reference_, gains, u.qc0, starts);
      const Eigen::VectorXd command = ctl.step(t, read_now, u.xi).cascade.u;
      drivePlant(next, drive.step(command, period, torque_steps).tau, period);
      next.xi = drive.state();
      ctl.step(t + period, readNext(), next.xi);
      next.qc0 = ctl.stage0().filterState();
      next.cascade = ctl.state();
    } else {
      Theorem1Controller ctl(*control_model_, reference_, paper_.gains, u.qc0);
      const Eigen::VectorXd command = ctl.step(t, read_now).u;
      drivePlant(next, drive.step(command, period, torque_steps).tau, period);
      ctl.step(t + period, readNext());
      next.qc0 = ctl.filterState();
    }
    return pack(next);
  }

  Eigen::MatrixXd jacobian(const Eigen::VectorXd& x, double t, double period, int torque_steps) const {
    const int d = size();
    Eigen::MatrixXd j(d, d);
    for (int c = 0; c < d; ++c) {
      const double h = 1e-6 * std::max(1.0, std::abs(x(c)));
      Eigen::VectorXd plus = x, minus = x;
      plus(c) += h;
      minus(c) -= h;
      j.col(c) = (step(plus, t, period, torque_steps) - step(minus, t, period, torque_steps)) / (2.0 * h);
    }
    return j;
  }

 private:
  struct Unpacked {
    Eigen::VectorXd q, v, q2, v2, qc0, rate;
    Eigen::MatrixXd xi, pending, seen;
    CascadeState cascade;
  };

  Unpacked zeros() const {
    Unpacked u;
    u.q = u.v = u.qc0 = Eigen::VectorXd::Zero(n_);
    if (flexible_) u.q2 = u.v2 = Eigen::VectorXd::Zero(n_);
    if (filtered_rate_) u.rate = Eigen::VectorXd::Zero(n_);
    u.xi = Eigen::MatrixXd::Zero(order_, n_);
    u.pending = Eigen::MatrixXd::Zero(delayed_ ? steps_ : 0, n_);
    u.seen = Eigen::MatrixXd::Zero(seen_, n_);
    u.cascade.qc = u.cascade.zeta = Eigen::MatrixXd::Zero(stages_, n_);
    return u;
  }

  Eigen::VectorXd pack(const Unpacked& u) const {
    Eigen::VectorXd x(size());
    int at = 0;
    auto put = [&](const Eigen::VectorXd& v) {
      x.segment(at, v.size()) = v, at += static_cast<int>(v.size());
    };
    auto putRows = [&](const Eigen::MatrixXd& m) {
      for (int i = 0; i < m.rows(); ++i) put(m.row(i).transpose());
    };
    put(u.q), put(u.v);
    if (flexible_) put(u.q2), put(u.v2);
    putRows(u.xi);
    put(u.qc0);
    putRows(u.cascade.qc + u.cascade.zeta);
    if (filtered_rate_) put(u.rate);
    putRows(u.pending);
    putRows(u.seen);
    return x;
  }

  Unpacked unpack(const Eigen::VectorXd& x) const {
    Unpacked u = zeros();
    int at = 0;
    auto take = [&](Eigen::VectorXd& v) { v = x.segment(at, n_), at += n_; };
    auto takeRows = [&](Eigen::MatrixXd& m) {
      for (int i = 0; i < m.rows(); ++i) m.row(i) = x.segment(at, n_).transpose(), at += n_;
    };
    take(u.q), take(u.v);
    if (flexible_) take(u.q2), take(u.v2);
    takeRows(u.xi);
    take(u.qc0);
    takeRows(u.cascade.qc);
    if (filtered_rate_) take(u.rate);
    takeRows(u.pending);
    takeRows(u.seen);
    return u;
  }

  // The plant over one period under the drive's output `rows`, now or (the
  // realtime wiring) after the rows pending from the previous sample.
  void drivePlant(Unpacked& next, const Eigen::MatrixXd& rows, double period) const {
    if (!delayed_) return integrate(next, rows, period);
    integrate(next, next.pending, period);
    next.pending = rows;
  }

  // The plant under the held torque rows, by RK4 of the analytic model. The
  // arm alone (torque held) is slow next to the period; the springs of a
  // flexible joint are not, so they set the RK4 step.
  void integrate(Unpacked& u, const Eigen::MatrixXd& rows, double period) const {
    const double row_period = period / static_cast<double>(rows.rows());
    double fastest = 50.0;  // [rad/s]: well above a rigid arm's own pendulum frequencies
    if (flexible_) {
      const Eigen::VectorXd& k = s_.flexible->params.stiffness;
      const double d_min = model::symmetricEigenvalues(control_model_->inertia(u.q)).minCoeff();
      for (int i = 0; i < n_; ++i)
        fastest = std::max(fastest, std::sqrt(k(i) / s_.flexible->params.rotor_inertia(i) + k(i) / d_min));
    }
    const int substeps = std::max(2, static_cast<int>(std::ceil(row_period * fastest / 0.1)));
    const double h = row_period / substeps;
    for (int r = 0; r < rows.rows(); ++r) {
      const Eigen::VectorXd tau = rows.row(r).transpose();
      for (int k = 0; k < substeps; ++k) rk4(u, tau, h);
    }
  }

  void rk4(Unpacked& u, const Eigen::VectorXd& tau, double h) const {
    if (flexible_) {
      using S = model::FlexibleState;
      auto f = [&](const S& x) {
        const auto acc = flexible_plant_->acceleration(x, tau);
        return S{x.v1, acc.first, x.v2, acc.second};
      };
      auto add = [](const S& x, const S& d, double c) {
        return S{x.q1 + c * d.q1, x.v1 + c * d.v1, x.q2 + c * d.q2, x.v2 + c * d.v2};
      };
      const S x{u.q, u.v, u.q2, u.v2};
      const S k1 = f(x), k2 = f(add(x, k1, h / 2)), k3 = f(add(x, k2, h / 2)), k4 = f(add(x, k3, h));
      u.q += h / 6 * (k1.q1 + 2 * k2.q1 + 2 * k3.q1 + k4.q1);
      u.v += h / 6 * (k1.v1 + 2 * k2.v1 + 2 * k3.v1 + k4.v1);
      u.q2 += h / 6 * (k1.q2 + 2 * k2.q2 + 2 * k3.q2 + k4.q2);
      u.v2 += h / 6 * (k1.v2 + 2 * k2.v2 + 2 * k3.v2 + k4.v2);
      return;
    }
    auto acc = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
      return arm_->acceleration(q, v, tau);
    };
    const Eigen::VectorXd q = u.q, v = u.v;
    const Eigen::VectorXd a1 = acc(q, v);
    const Eigen::VectorXd v2 = v + h / 2 * a1, a2 = acc(q + h / 2 * v, v2);
    const Eigen::VectorXd v3 = v + h / 2 * a2, a3 = acc(q + h / 2 * v2, v3);
    const Eigen::VectorXd v4 = v + h * a3, a4 = acc(q + h * v3, v4);
    u.q = q + h / 6 * (v + 2 * v2 + 2 * v3 + v4);
    u.v = v + h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
  }

  const config::Scenario& s_;
  const PaperSettings& paper_;  ///< s_'s controller section
  model::RobotModelPtr control_model_, arm_;
  model::Reference reference_;
  std::optional<model::FlexibleChain> flexible_plant_;
  int n_, order_, stages_;
  bool flexible_, filtered_rate_, delayed_;
  int seen_;  ///< d: samples the joint-angle reading lags
  int steps_;
};

double spectralRadius(const Eigen::MatrixXd& j) {
  return model::balancedEigenvalues(j).cwiseAbs().maxCoeff();
}

// Continuous modes at one instant: lambda = log(mu) / T_f from the map at a
// period T_f short enough that |log mu| <= 0.05 for every eigenvalue mu.
struct Modes {
  double slowest_decay = 0.0, fastest = 0.0;
  bool resolved = false;
};
Modes continuousModes(const LoopMap& loop, const Eigen::VectorXd& x, double t, double period) {
  double fine = period / 8.0;
  Modes m;
  for (int attempt = 0; attempt < 8 && t + fine > t + 0.5 * fine; ++attempt) {
    const Eigen::VectorXcd mu = model::balancedEigenvalues(loop.jacobian(x, t, fine, 1));
    double widest = 0.0;
    m.slowest_decay = INFINITY;
    m.fastest = 0.0;
    for (Eigen::Index i = 0; i < mu.size(); ++i) {
      const std::complex<double> lambda = std::log(mu(i)) / fine;
      widest = std::max(widest, std::abs(std::log(mu(i))));
      m.slowest_decay = std::min(m.slowest_decay, -lambda.real());
      m.fastest = std::max(m.fastest, std::abs(lambda));
    }
    if (std::isfinite(widest) && widest <= 0.05) {
      m.resolved = true;
      return m;
    }
    fine *= std::isfinite(widest) ? std::max(1e-3, 0.04 / widest) : 1e-3;
  }
  return m;
}

}  // namespace

namespace {
SampledDataCheck check(const config::Scenario& s) {
  SampledDataCheck c;
  c.rate = s.plant.publish_rate;
  c.one_period_delay = s.mode == config::Mode::kRealtime;
  // The map holds the joint-angle sensor's delay; a late motor-angle sensor
  // it does not model, and a long delay would make it too large to linearise
  // in seconds. Either way it says so rather than judge a loop it is not.
  if (s.sensors && s.sensors->motor && s.sensors->motor->delay > 0) {
    c.verdict = "not assessed";
    c.why = "the linearised map does not model the motor-angle sensor's delay (sensors.motor.delay " +
            std::to_string(s.sensors->motor->delay) + ")";
    return c;
  }
  if (s.sensors && s.sensors->position.delay > SampledDataCheck::kMaxSensorDelay) {
    c.verdict = "not assessed";
    c.why = "a joint-angle sensor " + std::to_string(s.sensors->position.delay) +
            " samples late is beyond the linearised map (at most " +
            std::to_string(SampledDataCheck::kMaxSensorDelay) + " samples)";
    return c;
  }
  // The map is the nominal lossless model's (eq. 10): a plant with damping,
  // friction, stops, a payload or model error is another loop, and the check
  // does not judge it.
  const config::PlantConfig& p = s.plant;
  auto any = [](const std::optional<Eigen::VectorXd>& v) { return v && (v->array() > 0.0).any(); };
  if (any(p.joint_damping) || any(p.joint_friction) || any(p.rotor_damping) || any(p.rotor_friction) ||
      p.urdf_dynamics || p.joint_limits || (p.payload && p.payload->mass > 0.0) ||
      (p.model_error &&
       (p.model_error->mass > 0.0 || p.model_error->inertia > 0.0 || p.model_error->com > 0.0))) {
    c.verdict = "not assessed";
    c.why =
        "the linearised map is the nominal lossless model's, without the plant's joint damping, "
        "friction, stops, payload or model error (plant.joint_damping, joint_friction, rotor_damping, "
        "rotor_friction, urdf_dynamics, joint_limits, payload, model_error); run the scenario to see the "
        "loop with them";
    return c;
  }
  const LoopMap loop(s, c.one_period_delay, true);
  // The continuous loop is the limit of either wiring as T -> 0: from the map without the delay.
  const LoopMap undelayed(s, false, false);
  const int steps = s.torqueStepsPerTick();
  std::vector<double> instants;
  std::vector<Eigen::VectorXd> points;
  for (int i = 0; i < SampledDataCheck::kInstants; ++i) {
    instants.push_back(s.duration * (i + 0.5) / SampledDataCheck::kInstants);
    points.push_back(loop.nominal(instants.back()));
  }
  // The largest spectral radius over the instants at a period, and where.
  auto worst = [&](double period, double* at) {
    double rho = 0.0;
    for (size_t i = 0; i < instants.size(); ++i) {
      const double r = spectralRadius(loop.jacobian(points[i], instants[i], period, steps));
      if (!(r <= rho)) rho = r, *at = instants[i];
    }
    return rho;
  };
  c.continuous_decay = INFINITY;
  for (size_t i = 0; i < instants.size(); ++i) {
    const Modes m = continuousModes(undelayed, undelayed.nominal(instants[i]), instants[i], s.tickPeriod());
    if (!m.resolved) {
      c.verdict = "not assessed";
      c.why =
          "the continuous loop's modes could not be resolved (a mode faster than 1e9 1/s, or a "
          "non-finite linearisation)";
      return c;
    }
    c.continuous_decay = std::min(c.continuous_decay, m.slowest_decay);
    c.fastest_mode = std::max(c.fastest_mode, m.fastest);
  }
  c.spectral_radius = worst(s.tickPeriod(), &c.worst_time);
  c.sampled_decay = -std::log(c.spectral_radius) * c.rate;
  if (!(c.continuous_decay > 0.0)) {
    c.verdict = "not assessed";
    c.why =
        "the continuous loop linearised along the reference has a mode that does not decay (slowest "
        "decay " +
        std::to_string(c.continuous_decay) + " 1/s): no sampling rate makes up for that";
    return c;
  }
  auto adequateAt = [&](double rho, double rate) {
    return rho < 1.0 && -std::log(rho) * rate >= SampledDataCheck::kAdequateFraction * c.continuous_decay;
  };
  char buf[256];
  if (adequateAt(c.spectral_radius, c.rate)) {
    c.verdict = "adequate";
    std::snprintf(buf, sizeof buf,
                  "the sampled loop's slowest mode decays at %.3g 1/s, %.0f %% of the continuous %.3g 1/s",
                  c.sampled_decay, 100.0 * c.sampled_decay / c.continuous_decay, c.continuous_decay);
    c.why = buf;
    return c;
  }
  c.verdict = c.spectral_radius >= 1.0 ? "unstable" : "slow";
  if (c.spectral_radius >= 1.0)
    std::snprintf(buf, sizeof buf,
                  "a mode of the sampled loop grows (|mu| = %.6g at t = %.3g s), while the continuous loop "
                  "decays at %.3g 1/s",
                  c.spectral_radius, c.worst_time, c.continuous_decay);
  else
    std::snprintf(
        buf, sizeof buf,
        "the sampled loop's slowest mode decays at %.3g 1/s, only %.0f %% of the continuous %.3g 1/s",
        c.sampled_decay, 100.0 * c.sampled_decay / c.continuous_decay, c.continuous_decay);
  c.why = buf;
  for (int k = 1; k <= 10; ++k) {
    const double rate = c.rate * std::pow(2.0, k);
    double at = 0.0;
    if (adequateAt(worst(1.0 / rate, &at), rate)) {
      c.sufficient_rate = rate;
      break;
    }
  }
  return c;
}

}  // namespace

SampledDataCheck checkSampledData(const config::Scenario& s) {
  if (!isPaperType(s.controller.type)) {
    SampledDataCheck c;
    c.rate = s.plant.publish_rate;
    c.verdict = "not assessed";
    c.why =
        "the sampled-data check linearises the paper's controllers (theorem1, cascaded, flexible); "
        "controller.type " +
        s.controller.type + " is not one of them";
    return c;
  }
  try {
    return check(s);
  } catch (const std::exception& e) {  // e.g. gains so large that a mode outruns double precision in time
    SampledDataCheck c;
    c.rate = s.plant.publish_rate;
    c.verdict = "not assessed";
    c.why = std::string("the linearisation failed: ") + e.what();
    return c;
  }
}

std::string describe(const SampledDataCheck& c) {
  char buf[768];
  std::string verdict = c.verdict;
  std::transform(verdict.begin(), verdict.end(), verdict.begin(), ::toupper);
  std::snprintf(buf, sizeof buf,
                "linearised check at %g Hz%s: %s: %s; spectral radius %.6g (t = %.3g s), fastest continuous "
                "mode |lambda| T = %.3g",
                c.rate, c.one_period_delay ? " with the realtime wiring's one-period delay" : "",
                verdict.c_str(), c.why.c_str(), c.spectral_radius, c.worst_time, c.fastestModeTimesPeriod());
  std::string out = buf;
  if (!c.adequate() && c.verdict != "not assessed")
    out += c.sufficient_rate ? "; " + std::to_string(static_cast<long long>(*c.sufficient_rate)) +
                                   " Hz would suffice (plant.publish_rate)"
                             : "; no rate up to 1024 x this one suffices";
  out += "  [estimate, local: the discretised loop linearised along the reference at " +
         std::to_string(SampledDataCheck::kInstants) +
         " instants, the cores as implemented, the plant's model by RK4; see docs/sampled_data.md]";
  return out;
}

namespace {
// What one loop did: "converged at 0.915 s", "did not converge within the run", "diverged".
std::string outcome(const std::string& status, const std::optional<double>& t) {
  if (status != "completed") return "diverged";
  if (!t) return "did not converge within the run";
  char buf[48];
  std::snprintf(buf, sizeof buf, "converged at %.3g s", *t);
  return buf;
}
}  // namespace

std::string describe(const SampledSimulation& c) {
  std::string verdict = c.verdict;
  std::transform(verdict.begin(), verdict.end(), verdict.begin(), ::toupper);
  char head[160];
  // "UNSTABLE about the reference: ..." reads as one sentence (its why begins "from").
  std::snprintf(head, sizeof head, "sampled-data check at %g Hz%s: %s%s", c.rate,
                c.one_period_delay ? " with the realtime wiring's one-period delay" : "", verdict.c_str(),
                c.verdict == "unstable" && c.why.rfind("about the reference", 0) == 0 ? " " : ": ");
  std::string out = head + c.why;
  for (const SampledSimulation::Start& s : c.starts) {
    char line[320];
    std::snprintf(
        line, sizeof line,
        "\n  from %s: the sampled loop %s, the fine-rate loop %s; RMS error of the last second %.3g rad "
        "(fine: %.3g)",
        s.what.c_str(), outcome(s.sampled_status, s.sampled_time).c_str(),
        outcome(s.fine_status, s.fine_time).c_str(), s.sampled_error, s.fine_error);
    out += line;
  }
  if (c.starts.empty()) return out;  // nothing simulated (not assessed): no evidence to qualify
  char tail[320];
  std::snprintf(
      tail, sizeof tail,
      "\n  [evidence from these %zu states, not a proof for all: in-process simulations of %g s, the "
      "loop as configured at %g Hz against the same plant and controller at %g Hz with exact sensors "
      "(%s); %.1f s; see docs/sampled_data.md]",
      c.starts.size(), c.duration, c.rate, c.fine_rate,
      c.confirmed_at
          ? ("the same loop at " + std::to_string(static_cast<long long>(*c.confirmed_at)) + " Hz agrees")
                .c_str()
          : "no finer rate up to the cap agreed with it",
      c.wall_time);
  return out + tail;
}

}  // namespace lagrange::controller
