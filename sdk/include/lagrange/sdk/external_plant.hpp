#pragma once
/// @file
/// lagrange's C++ SDK: a plant of your own in a lagrange run (plant.type:
/// external) -- a simulator you wrote, or a bridge to a real arm
/// (docs/hardware.md) --, built outside this tree against the installed
/// package:
///
///     find_package(lagrange REQUIRED)
///     find_package(nlohmann_json 3 REQUIRED)   # the scenario is read with it (scenario.hpp)
///     target_link_libraries(my_plant PRIVATE lagrange::sdk nlohmann_json::nlohmann_json)
///
/// You write how the arm moves over one period; runPlant() keeps the
/// plant's side of docs/external_programs.md, as the Python module
/// lagrange.external_plant does: the run's LCM URL, id, key and joint count
/// from the environment, the MAC and header on every datagram, the run's
/// clock (lockstep: a tick goes out once the logger is at most
/// lockstep.logger_window behind, its position re-sent until the actuator
/// answers, unconfirmed ticks re-sent to the logger; realtime: a fixed-rate
/// loop with the scenario's stale-torque policy), PLANT_POSITION and
/// PLANT_TRUTH of every tick, the STATUS handshake, and the guards a bridge
/// needs (PlantLimits, a watchdog):
///
///     int main() {
///       return lagrange::sdk::runPlant([&](double t, const std::vector<double>& u, double dt) {
///         lagrange::sdk::PlantState s;   // the arm at t + dt, u [N m] held from t
///         ...
///         return s;
///       });
///     }

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/sdk/external_controller.hpp"
#include "lagrange/sdk/scenario.hpp"

namespace lagrange::sdk {

/// The arm at one instant: joint angles q [rad] and rates qdot [rad/s], one
/// per joint, and its energies [J] (logged in PLANT_TRUTH; NaN: not known).
struct PlantState {
  std::vector<double> q, qdot;
  double kinetic_energy = std::numeric_limits<double>::quiet_NaN();
  double potential_energy = std::numeric_limits<double>::quiet_NaN();

  /// What runPlant asks of every state it is given: q and qdot one finite
  /// value per joint; each energy finite, or NaN (not known) -- never
  /// infinite. @throws ContractError naming `what` ("step() at t = 0.5 s",
  /// "initial()"), the field, its joint and value.
  void check(int joints, const std::string& what) const;
};

/// What a bridge enforces whatever the controller asks (docs/hardware.md);
/// an empty optional: no limit of that kind.
///  - torque: |u_i| <= torque[i] [N m]; a larger command is clipped (counted);
///  - position: lower_i <= q_i <= upper_i [rad], as {lower, upper} per joint;
///  - rate: |qdot_i| <= rate[i] [rad/s].
/// A state outside its position or rate limits stops the run: STATUS
/// "failed" naming joint, value, limit and tick, brake() when given, exit 1.
struct PlantLimits {
  std::optional<std::vector<double>> torque;
  std::optional<std::vector<std::pair<double, double>>> position;
  std::optional<std::vector<double>> rate;

  /// @throws ContractError naming the limits that are not > 0, not
  ///         lower < upper, or not one per joint.
  void check(int joints) const;
  /// u within the torque limits, and whether any entry was clipped.
  std::pair<std::vector<double>, bool> clip(const std::vector<double>& u) const;
  /// What the state crosses, as a sentence ("joint 2's rate 9 rad/s is
  /// beyond its limit 5"), or nothing.
  std::optional<std::string> breach(const std::vector<double>& q, const std::vector<double>& qdot) const;
};

/// The actuator's answers as a plant takes them (valid ACTUATOR_STATEs only):
///  - lockstep: tick k is answered by the first state whose tick is k -- a
///    stale (earlier tick), repeated (re-sent) or future tick's changes
///    nothing --, and that state's torque is the one applied after k;
///  - realtime: the newest state, whichever tick, is what TorqueChoice
///    chooses from.
class ActuatorAnswers {
 public:
  /// Lockstep: tick k went out and its answer is awaited (any earlier one forgotten).
  void await(int64_t k);
  /// A valid ACTUATOR_STATE of `tick`; whether it is the awaited tick's answer.
  bool take(int64_t tick, const std::vector<double>& tau, int64_t publish_utime);

  /// The awaited tick; none before the first await().
  std::optional<int64_t> awaited() const { return awaited_; }
  /// Whether the awaited tick has its answer.
  bool answered() const { return answered_; }
  /// The awaited tick's answer (empty while unanswered).
  const std::vector<double>& answer() const { return answer_; }

  /// The newest state's tick; none before the first.
  std::optional<int64_t> newestTick() const { return newest_tick_; }
  const std::vector<double>& newestTorque() const { return newest_tau_; }
  /// Its publish_utime (the run's clock) [us].
  int64_t newestUtime() const { return newest_utime_; }

 private:
  std::optional<int64_t> awaited_;
  bool answered_ = false;
  std::vector<double> answer_;
  std::optional<int64_t> newest_tick_;
  std::vector<double> newest_tau_;
  int64_t newest_utime_ = 0;
};

/// How the torque of a period was chosen (plant_truth_t.torque_source).
enum class TorqueSource : int8_t { kCommanded = 0, kHeld = 1, kZero = 2 };

/// Which torque a realtime plant applies over the period after tick k (the
/// built-in plant's rule, plant/plant_loops.cpp): the newest answer while
/// at most max_age ticks old; then, with hold (stale_torque "hold"), that
/// torque for hold_periods more; then zero. The watchdog (watchdog_periods;
/// none: off) zeroes an answer older than that whatever the policy, and
/// trips once per silence.
class TorqueChoice {
 public:
  struct Choice {
    std::vector<double> tau;  ///< [N m], one per joint
    TorqueSource source;
    int64_t input_tick;  ///< the ACTUATOR_STATE tick applied; -1 for zero torque
    bool tripped_now;    ///< the watchdog tripped at this tick (the first of a silence)
  };

  TorqueChoice(int max_age, int hold_periods, bool hold, std::optional<int> watchdog_periods = std::nullopt);

  /// The torque over the period after tick k, given the newest answer (its
  /// tick and torque; no tick: none yet). Counts held and zeroed periods,
  /// but none at k = 0, before which nothing can have answered.
  Choice choose(int64_t k, std::optional<int64_t> newest_tick, const std::vector<double>& newest_tau,
                int joints);

  int64_t held() const { return held_; }
  int64_t zeroed() const { return zeroed_; }
  int64_t watchdogTrips() const { return watchdog_trips_; }
  std::optional<int> watchdogPeriods() const { return watchdog_; }

 private:
  int max_age_;
  int hold_limit_;
  std::optional<int> watchdog_;
  int64_t held_ = 0, zeroed_ = 0, watchdog_trips_ = 0;
  bool tripped_ = false;
};

/// How the arm moves: u [N m] (one per joint) applied from t [s] for dt [s]
/// -> the state at t + dt. A state with the wrong number of values, or a
/// value that is not finite, stops the run naming it, its joint and t.
using PlantStep = std::function<PlantState(double t, const std::vector<double>& u, double dt)>;

struct PlantOptions {
  std::optional<PlantLimits> limits;
  /// Realtime: an answer older than this many periods is replaced by zero
  /// torque (and brakes, once per silence). Off in lockstep, where waiting for
  /// each answer is the protocol (lockstep.stall_timeout ends a stalled run);
  /// said once in plant.log. Whole periods >= 1; none: off.
  std::optional<int> watchdog_periods;
  /// The bridge's own way to make the arm safe (zero torque, the brakes):
  /// called when the realtime watchdog trips, and once on every end but "finished" --
  /// a crossed limit, a stall, an error of step() or initial(), a stop by
  /// SIGTERM or SIGINT --, "plant: calling brake()" on stderr first.
  std::function<void()> brake;
  /// The state at t = 0 (a bridge reads the arm); none: the scenario's initial_state.
  std::function<PlantState()> initial;
};

/// What runPlant takes from the run's resolved scenario.
struct PlantScenario {
  std::string mode;                 ///< "lockstep" or "realtime"
  double publish_rate = 0.0;        ///< plant.publish_rate [Hz]: one tick a period
  double duration = 0.0;            ///< [s]
  double retransmit_timeout = 0.0;  ///< lockstep.retransmit_timeout [s]
  int logger_window = 0;            ///< lockstep.logger_window [ticks]
  double stall_timeout = 0.0;       ///< lockstep.stall_timeout [s]
  int max_torque_age = 0;           ///< realtime.max_torque_age [ticks]
  int hold_periods = 0;             ///< realtime.hold_periods
  bool hold = false;                ///< realtime.stale_torque == "hold"
  std::vector<double> q0, qdot0;    ///< initial_state

  /// @throws ContractError naming the value the scenario lacks or mistypes.
  static PlantScenario from(const nlohmann::json& s) {
    try {
      const auto& lockstep = s.at("lockstep");
      const auto& realtime = s.at("realtime");
      PlantScenario p;
      p.mode = s.at("mode").get<std::string>();
      p.publish_rate = s.at("plant").at("publish_rate").get<double>();
      p.duration = s.at("duration").get<double>();
      p.retransmit_timeout = lockstep.at("retransmit_timeout").get<double>();
      p.logger_window = lockstep.at("logger_window").get<int>();
      p.stall_timeout = lockstep.at("stall_timeout").get<double>();
      p.max_torque_age = realtime.at("max_torque_age").get<int>();
      p.hold_periods = realtime.at("hold_periods").get<int>();
      p.hold = realtime.at("stale_torque").get<std::string>() == "hold";
      p.q0 = s.at("initial_state").at("q").get<std::vector<double>>();
      p.qdot0 = s.at("initial_state").at("qdot").get<std::vector<double>>();
      return p;
    } catch (const nlohmann::json::exception& e) {
      throw ContractError(
          std::string("the run's scenario (LAGRANGE_CONFIG_JSON) lacks a value the plant needs, "
                      "or has one of another type: ") +
          e.what() + "; expected the resolved scenario lagrange wrote");
    }
  }
};

/// runPlant's work, with the scenario read by `read_scenario` (called once,
/// inside its error handling). Use runPlant.
int servePlant(const PlantStep& step, const PlantOptions& options,
               const std::function<PlantScenario()>& read_scenario);

/// Serves `step` as the run's plant until the run's last tick, then returns
/// 0 (also when stopped by SIGTERM or SIGINT: STATUS "interrupted"). A
/// stall (naming whom it waited for and what it heard), a crossed limit, a
/// broken contract or an exception from step() or initial() is printed to
/// stderr, published as STATUS "failed", and returns 1: `return
/// lagrange::sdk::runPlant(step);` from main. Every end but "finished"
/// calls options.brake once, when given. Installs handlers of SIGTERM,
/// SIGINT and SIGCONT (the launcher restarted a peer: start-up time again)
/// while it runs.
inline int runPlant(const PlantStep& step, const PlantOptions& options = {}) {
  return servePlant(step, options, [] { return PlantScenario::from(scenario()); });
}

}  // namespace lagrange::sdk
