#pragma once
/// @file
/// Is the sampled implementation adequate at the configured rate? The paper's
/// conditions (eq. (12), (632), Theorem 6) are about the continuous-time loop; a
/// controller running at 1 kHz can converge far slower than that loop, or not
/// at all, while eq. (12) holds with a wide margin -- e.g. uniform gains on an
/// arm whose lightest joint then has a closed-loop mode near the sampling rate.
///
/// Method: the linearisation of the discretised closed loop along the reference.
///  - The one-period map x_k -> x_{k+1} of the whole loop, with the controller
///    core of the scenario exactly as implemented (its filters discretised
///    exactly, the same classes the processes run), the actuator's integrator
///    chain (with actuator.rate's torque steps), and the plant's dynamics under
///    the zero-order-held torque, integrated by RK4 of the analytic model (595
///    for flexible joints). The state: q, q' (and q2, q2'), the actuator's xi,
///    and every filter state of the controller.
///  - Its Jacobian by central differences at the reference, frozen at
///    kInstants instants spread over the run (q = q_d(t), q' = q_d'(t), filters
///    at rest, the actuator at the feedforward torque), and the spectral radius
///    rho of each; the largest is reported with its instant.
///  - The continuous loop's modes lambda from the same map at a period short
///    enough that |lambda| T_f <= 0.05 (lambda = log(mu) / T_f): the slowest
///    decay sigma_c = -max Re lambda and the fastest |lambda|.
///  - Verdict: "adequate" when rho < 1 and the sampled loop's slowest mode,
///    sigma_d = -ln(rho) / T, decays at least kAdequateFraction as fast as
///    the continuous loop's (sigma_d >= 0.5 sigma_c); "slow" when rho < 1 but
///    not that fast; "unstable" when rho >= 1. Otherwise the smallest rate of
///    rate x 2^k (k <= 10) that is adequate is reported as sufficient.
///  - The realtime wiring (mode realtime) is modelled with its one period of
///    delay: the plant steps over [t_k, t_{k+1}] with the torque that answered
///    q(t_{k-1}), so the drive's output waits a period in the map's state.
///    Lockstep and in-process runs apply the torque answering q(t_k) at once.
///  - A joint-angle sensor d samples late (sensors.position.delay, d <=
///    kMaxSensorDelay) is modelled too: the map keeps the last d angles and
///    the controller reads q(t_{k-d}). The continuous loop it is compared with
///    has no delay (d samples vanish as T -> 0). A late motor-angle sensor, or
///    a longer delay, is "not assessed", with why.
/// Limits (it is an estimate, and says so): it is local (small errors: the
/// global question is the theorems'), frozen in time (exact for a set point,
/// an approximation for references slow next to the loop), ignores actuator
/// saturation, the sensors' noise and quantisation, the realtime wiring's
/// late and lost messages and ODE's integration error, and samples kInstants
/// instants, not every t.

#include <optional>
#include <string>
#include <vector>

#include "config/scenario.hpp"

namespace lagrange::controller {

struct SampledDataCheck {
  static constexpr int kInstants = 8;
  static constexpr double kAdequateFraction = 0.5;
  /// The longest joint-angle sensor delay the map models [samples].
  static constexpr int kMaxSensorDelay = 10;

  double rate = 0.0;                      ///< the controller rate examined [Hz] (plant.publish_rate)
  double spectral_radius = 0.0;           ///< rho: largest over the instants
  double worst_time = 0.0;                ///< the instant of that largest rho [s]
  double sampled_decay = 0.0;             ///< sigma_d = -ln(rho) / T [1/s] (negative: growth)
  double continuous_decay = 0.0;          ///< sigma_c = min over instants of -max Re lambda [1/s]
  double fastest_mode = 0.0;              ///< max |lambda| of the continuous loop [1/s]
  std::string verdict;                    ///< "adequate", "slow", "unstable" or "not assessed"
  std::string why;                        ///< one sentence behind the verdict
  std::optional<double> sufficient_rate;  ///< when not adequate: a rate that is [Hz]
  /// The realtime wiring: the torque answering q(t_k) acts over [t_{k+1}, t_{k+2}]
  /// (lockstep and in-process: over [t_k, t_{k+1}]).
  bool one_period_delay = false;

  bool adequate() const { return verdict == "adequate"; }
  /// fastest_mode T: how close the fastest continuous mode is to the sampling rate.
  double fastestModeTimesPeriod() const { return fastest_mode / rate; }
};

/// The check for the scenario's controller at its plant.publish_rate.
SampledDataCheck checkSampledData(const config::Scenario& scenario);

/// One line a person reads.
std::string describe(const SampledDataCheck& check);

/// The sampled loop simulated (wiring/sampled_simulation.hpp computes it; the
/// data and its words are here, beside the linearised check's): the scenario
/// as configured, in process, from its initial state and a few seeded states
/// of the same error norm, against the same loop at a fine rate that stands
/// for continuous time. True for these states by construction; evidence from
/// them, not a proof for all.
struct SampledSimulation {
  /// ADEQUATE when the sampled loop converges within this factor of the fine
  /// loop's time (and two periods); OFFSET, where neither reaches the
  /// tolerance, when its steady-state error is within this factor of the fine
  /// loop's (and a quarter of the tolerance).
  static constexpr double kSlack = 1.25;
  /// Every word `verdict` takes, best first (the worst start's decides).
  static constexpr const char* kVerdicts[] = {"adequate", "offset",   "not assessed",
                                              "slow",     "unstable", "diverges"};

  /// One start: where from, and what each loop did.
  struct Start {
    std::string what;            ///< "the initial state", "seeded state 1", ...
    std::string sampled_status;  ///< "completed", or "diverged" (the simulation was stopped)
    std::string fine_status;
    std::optional<double> sampled_time;  ///< convergence time [s]; none: not within the run
    std::optional<double> fine_time;
    double sampled_error = 0.0;  ///< RMS of ||q~|| over the last second [rad]
    double fine_error = 0.0;
    std::string verdict;         ///< as the overall one, for this start
    double initial_error = 0.0;  ///< ||q(0) - q_d(0)|| [rad]
  };

  double rate = 0.0;       ///< the configured rate [Hz]
  double fine_rate = 0.0;  ///< the rate standing for continuous time [Hz]
  /// The finer rate that confirmed fine_rate (the initial state's loop the
  /// same at both), or none when no rate up to the cap agreed.
  std::optional<double> confirmed_at;
  double duration = 0.0;   ///< each simulation's length [s]
  double tolerance = 0.0;  ///< metrics.tolerance [rad]
  /// The realtime wiring's one period of delay, simulated as one sample of
  /// joint-angle sensor delay (the same lag, the reference a period apart).
  bool one_period_delay = false;
  std::vector<Start> starts;
  /// The first word of the verdict, the worst start's (kVerdicts, best first):
  ///  - "adequate": the sampled loop converged within kSlack of the fine loop's
  ///    time and two periods (where the fine loop keeps an offset: it converged);
  ///  - "offset": neither loop reaches the tolerance and the sampled one ends
  ///    within kSlack of the fine one's error: a steady offset sampling does
  ///    not cause; `why` names the likely cause (what the plant has that the
  ///    controller does not model: damping, friction, a payload, ...);
  ///  - "not assessed": the fine loop itself was stopped, no fine rate was
  ///    confirmed (for adequate and offset), or the loop is not in process;
  ///  - "slow": the sampled loop converges later than the fine one, or ends
  ///    farther off, while a start near the reference converges (stable about it);
  ///  - "unstable": the same, but the sampled loop started near the reference
  ///    (torque limits lifted) grows: unstable about the reference; `why` adds
  ///    "held off only by saturation" when the limits are what keeps the
  ///    configured loop bounded;
  ///  - "diverges": the sampled simulation was stopped, or the loop ended
  ///    farther from the reference than it started.
  std::string verdict;
  std::string why;         ///< one sentence behind the verdict
  double wall_time = 0.0;  ///< what the simulations took [s]

  bool adequate() const { return verdict == "adequate"; }
  /// A failed check (check-gains exits 1, run --strict refuses): the sampled
  /// loop is unstable about the reference, or diverges. "slow" and "offset"
  /// warn only ("offset" is not sampling's doing).
  bool fails() const { return verdict == "unstable" || verdict == "diverges"; }
};

/// What a person reads: the verdict, the times, and what it rests on.
std::string describe(const SampledSimulation& simulation);

}  // namespace lagrange::controller
