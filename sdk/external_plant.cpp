#include "lagrange/sdk/external_plant.hpp"

#include <sched.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <map>
#include <memory>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/loop_stats_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "lagrange/status_t.hpp"
#include "sdk/contract.hpp"

namespace lagrange::sdk {

static_assert(static_cast<int8_t>(TorqueSource::kCommanded) == lagrange::plant_truth_t::TORQUE_COMMANDED &&
                  static_cast<int8_t>(TorqueSource::kHeld) == lagrange::plant_truth_t::TORQUE_HELD &&
                  static_cast<int8_t>(TorqueSource::kZero) == lagrange::plant_truth_t::TORQUE_ZERO,
              "TorqueSource is plant_truth_t's torque_source");

namespace {

// The messages say numbers as the Python module does (%.6g, %g), so a plant
// reads the same whichever SDK it was written with.
__attribute__((format(printf, 1, 2))) std::string format(const char* pattern, ...) {
  va_list args;
  va_start(args, pattern);
  va_list again;
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, pattern, args);
  va_end(args);
  std::string out(static_cast<size_t>(std::max(size, 0)) + 1, '\0');
  std::vsnprintf(out.data(), out.size(), pattern, again);
  va_end(again);
  out.resize(static_cast<size_t>(std::max(size, 0)));
  return out;
}

std::string listOf(const std::vector<double>& v) {
  std::string out = "[";
  for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + format("%.6g", v[i]);
  return out + "]";
}

std::string listOf(const std::vector<std::pair<double, double>>& v) {
  std::string out = "[";
  for (size_t i = 0; i < v.size(); ++i)
    out += (i ? ", " : "") + format("(%.6g, %.6g)", v[i].first, v[i].second);
  return out + "]";
}

void checkPositive(const char* what, const std::optional<std::vector<double>>& limits) {
  if (limits && !std::all_of(limits->begin(), limits->end(), [](double x) { return x > 0.0; }))
    throw ContractError(
        format("PlantLimits: every %s limit must be > 0; got %s", what, listOf(*limits).c_str()));
}

template <class V>
void checkCount(const char* what, const std::optional<V>& limits, int joints) {
  if (limits && static_cast<int>(limits->size()) != joints)
    throw ContractError(format("PlantLimits: %zu %s limits for %d joints; expected one per joint",
                               limits->size(), what, joints));
}

void checkValues(const std::vector<double>& v, const char* name, int joints, const std::string& what) {
  if (static_cast<int>(v.size()) != joints)
    throw ContractError(format("%s returned %zu numbers for %s; expected %d (one per joint)", what.c_str(),
                               v.size(), name, joints));
  for (size_t j = 0; j < v.size(); ++j)
    if (!std::isfinite(v[j]))
      throw ContractError(format("%s returned %g for %s[%zu] (joint %zu); expected finite numbers",
                                 what.c_str(), v[j], name, j, j + 1));
}

}  // namespace

void PlantState::check(int joints, const std::string& what) const {
  checkValues(q, "q", joints, what);
  checkValues(qdot, "qdot", joints, what);
  // Each state its own energies; NaN: not known. An infinite one is a mistake.
  for (const auto& [name, value] : {std::make_pair("kinetic_energy", kinetic_energy),
                                    std::make_pair("potential_energy", potential_energy)})
    if (std::isinf(value))
      throw ContractError(format("%s returned %g for %s; expected a finite number [J], or NaN (not known)",
                                 what.c_str(), value, name));
}

void ActuatorAnswers::await(int64_t k) {
  awaited_ = k;
  answered_ = false;
  answer_.clear();
}

bool ActuatorAnswers::take(int64_t tick, const std::vector<double>& tau, int64_t publish_utime) {
  if (!newest_tick_ || tick > *newest_tick_) {  // realtime: the newest, whichever tick
    newest_tick_ = tick;
    newest_tau_ = tau;
    newest_utime_ = publish_utime;
  }
  // Lockstep: the first state of the awaited tick; a stale, repeated or future one changes nothing.
  if (answered_ || !awaited_ || tick != *awaited_) return false;
  answered_ = true;
  answer_ = tau;
  return true;
}

void PlantLimits::check(int joints) const {
  checkPositive("torque", torque);
  checkPositive("rate", rate);
  if (position &&
      !std::all_of(position->begin(), position->end(), [](const auto& p) { return p.first < p.second; }))
    throw ContractError("PlantLimits: every position limit must be {lower, upper} with lower < upper; got " +
                        listOf(*position));
  checkCount("torque", torque, joints);
  checkCount("position", position, joints);
  checkCount("rate", rate, joints);
}

std::pair<std::vector<double>, bool> PlantLimits::clip(const std::vector<double>& u) const {
  if (!torque) return {u, false};
  std::vector<double> out(u);
  for (size_t i = 0; i < out.size() && i < torque->size(); ++i)
    out[i] = std::max(-(*torque)[i], std::min((*torque)[i], u[i]));
  return {out, out != u};
}

std::optional<std::string> PlantLimits::breach(const std::vector<double>& q,
                                               const std::vector<double>& qdot) const {
  for (size_t j = 0; j < q.size(); ++j) {
    // Negated comparisons: a NaN is outside every limit.
    if (position && j < position->size()) {
      const auto [lo, hi] = (*position)[j];
      if (!(lo <= q[j] && q[j] <= hi))
        return format("joint %zu's position %.6g rad is outside its limits [%.6g, %.6g]", j + 1, q[j], lo,
                      hi);
    }
    if (rate && j < rate->size() && j < qdot.size() && !(std::abs(qdot[j]) <= (*rate)[j]))
      return format("joint %zu's rate %.6g rad/s is beyond its limit %.6g", j + 1, qdot[j], (*rate)[j]);
  }
  return std::nullopt;
}

TorqueChoice::TorqueChoice(int max_age, int hold_periods, bool hold, std::optional<int> watchdog_periods)
    : max_age_(max_age), hold_limit_(hold ? max_age + hold_periods : max_age), watchdog_(watchdog_periods) {}

TorqueChoice::Choice TorqueChoice::choose(int64_t k, std::optional<int64_t> newest_tick,
                                          const std::vector<double>& newest_tau, int joints) {
  const std::vector<double> zero(static_cast<size_t>(joints), 0.0);
  const int64_t age = newest_tick ? k - *newest_tick : k + 1;
  if (watchdog_ && age > *watchdog_) {
    const bool tripped_now = !tripped_;
    if (tripped_now) ++watchdog_trips_;
    tripped_ = true;
    if (k > 0) ++zeroed_;
    return {zero, TorqueSource::kZero, -1, tripped_now};
  }
  tripped_ = false;
  if (newest_tick && age <= max_age_) return {newest_tau, TorqueSource::kCommanded, *newest_tick, false};
  if (newest_tick && age <= hold_limit_) {
    ++held_;
    return {newest_tau, TorqueSource::kHeld, *newest_tick, false};
  }
  if (k > 0) ++zeroed_;  // nothing can have answered before the first sample
  return {zero, TorqueSource::kZero, -1, false};
}

namespace {

/// The plant ended the run: a stall (whom it waited for), a limit crossed.
class PlantStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A user's function (step(), initial(), brake()) threw: what it said, with
/// which function and when.
class UserError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// f(), what it throws becoming a UserError naming `what` ("step() at t = 0.5 s").
template <class F>
auto callUser(const F& f, const std::string& what) -> decltype(f()) {
  try {
    return f();
  } catch (const std::exception& e) {
    throw UserError(what + " failed: " + (*e.what() != '\0' ? e.what() : "an exception without a message"));
  } catch (...) {
    throw UserError(what + " failed: it threw something that is not a std::exception");
  }
}

int64_t monotonicNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

double seconds() { return static_cast<double>(monotonicNs()) * 1e-9; }

// Set by the signal handlers, read by the loops (at least every 5 ms).
volatile std::sig_atomic_t g_stop_signal = 0;
volatile std::sig_atomic_t g_resumed = 0;

extern "C" void noteStop(int signum) { g_stop_signal = signum; }
extern "C" void noteResume(int) { g_resumed = 1; }

// SIGTERM and SIGINT stop the plant (STATUS "interrupted"); SIGCONT -- the
// launcher restarted a peer, or the plant was stopped -- gives the waits
// their start-up time again. Without SA_RESTART, so a wait wakes to look.
// The program's own handlers come back when the plant is done.
class SignalScope {
 public:
  SignalScope() {
    g_stop_signal = 0;
    g_resumed = 0;
    install(SIGTERM, noteStop, 0);
    install(SIGINT, noteStop, 1);
    install(SIGCONT, noteResume, 2);
  }
  ~SignalScope() {
    sigaction(SIGTERM, &old_[0], nullptr);
    sigaction(SIGINT, &old_[1], nullptr);
    sigaction(SIGCONT, &old_[2], nullptr);
  }
  SignalScope(const SignalScope&) = delete;
  SignalScope& operator=(const SignalScope&) = delete;

 private:
  void install(int signum, void (*handler)(int), int slot) {
    struct sigaction action {};
    action.sa_handler = handler;
    sigemptyset(&action.sa_mask);
    sigaction(signum, &action, &old_[slot]);
  }
  struct sigaction old_[3]{};
};

bool stopRequested() { return g_stop_signal != 0; }

bool takeResume() {
  const bool resumed = g_resumed != 0;
  g_resumed = 0;
  return resumed;
}

void warn(const std::string& line) { std::cerr << "plant: " << line << std::endl; }

/// Percentiles of non-negative durations in fixed memory (1 % buckets), as the Python module's.
/// NaN while empty: loop_stats_t says "not measured" so, never 0 s.
class Lateness {
 public:
  void add(double s) {
    ++counts_[static_cast<int>(std::log1p(std::max(0.0, s) * 1e7) / kStep)];
    ++n_;
    max_ = n_ == 1 ? s : std::max(max_, s);
  }
  double percentile(double p) const {
    if (n_ == 0) return std::numeric_limits<double>::quiet_NaN();
    const double want = p * static_cast<double>(n_);
    int64_t seen = 0;
    for (const auto& [bucket, count] : counts_) {
      seen += count;
      if (static_cast<double>(seen) >= want) return std::expm1(bucket * kStep) * 1e-7;
    }
    return max_;
  }
  double max() const { return max_; }
  int64_t count() const { return n_; }

 private:
  static constexpr double kStep = 0.009950330853168083;  // log(1.01)
  std::map<int, int64_t> counts_;
  int64_t n_ = 0;
  double max_ = std::numeric_limits<double>::quiet_NaN();
};

// A realtime period's reading of what arrived: kDrainLate datagrams even when
// the loop is behind schedule (one ACTUATOR_STATE a period and a few STATUS
// fit many times over), up to kDrainMax while the period lasts. The Python
// module's DRAIN_LATE and DRAIN_MAX.
constexpr int kDrainLate = 64;
constexpr int kDrainMax = 1000;
// Publication times of the recent positions, for the latency (a ring, as the built-in plant's).
constexpr int64_t kLatencyRing = 4096;

// "fifo:50 cpus 1,3" or "other": what the loop ran under, as loop_stats_t says it.
std::string schedulerNow() {
  sched_param param{};
  sched_getparam(0, &param);
  std::string out = sched_getscheduler(0) == SCHED_FIFO ? format("fifo:%d", param.sched_priority) : "other";
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) < sysconf(_SC_NPROCESSORS_ONLN)) {
    std::string cpus;
    for (int c = 0; c < CPU_SETSIZE; ++c)
      if (CPU_ISSET(c, &set)) cpus += (cpus.empty() ? "" : ",") + std::to_string(c);
    out += " cpus " + cpus;
  }
  return out;
}

void publishStatus(contract::Bus& bus, double period, const std::string& state, int64_t last_tick,
                   const std::string& message, const lagrange::loop_stats_t& loop) {
  lagrange::status_t s{};
  s.process = "plant";
  s.state = state;
  s.last_tick = last_tick;
  s.tracking_error = std::numeric_limits<double>::quiet_NaN();
  s.message = message;
  s.num_channels = 0;
  s.loop = loop;
  const int64_t tick = std::max<int64_t>(last_tick, 0);
  bus.publish("STATUS", s, tick, static_cast<double>(tick) * period);
}

/// One tick's measurements, kept until the logger confirms them.
struct Sample {
  int64_t k = 0;
  double t = 0.0;
  lagrange::plant_position_t position;
  lagrange::plant_truth_t truth;
};

class Plant {
 public:
  Plant(contract::Bus& bus, const PlantStep& step, const PlantOptions& options, const PlantScenario& s)
      : bus_(bus),
        step_(step),
        options_(options),
        scenario_(s),
        joints_(static_cast<int>(contract::integer("LAGRANGE_JOINTS", "plant"))),
        period_(1.0 / s.publish_rate),
        last_tick_(std::llround(s.duration * s.publish_rate)),
        startup_(3.0 * s.stall_timeout),  // plant/plant_loops.hpp startupTimeout
        choice_(s.max_torque_age, s.hold_periods, s.hold, options.watchdog_periods) {
    checkSettings();
    if (options_.initial)
      take(callUser(options_.initial, "initial()"), "initial()");
    else
      take(
          {s.q0, s.qdot0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()},
          "the scenario's initial_state");
    bus_.lcm().subscribe("ACTUATOR_STATE", &Plant::onActuatorState, this);
    bus_.lcm().subscribe("STATUS", &Plant::onStatus, this);
  }

  int serve() {
    checkLimits(0);
    return scenario_.mode == "realtime" ? serveRealtime() : serveLockstep();
  }

  /// Whether the run reached its end ("finished"), rather than a stop.
  bool finished() const { return finished_; }

 private:
  void checkSettings() const {
    if (joints_ < 1)
      throw ContractError(format("LAGRANGE_JOINTS is %d; expected a number of joints >= 1", joints_));
    if (scenario_.mode != "lockstep" && scenario_.mode != "realtime")
      throw ContractError("the run's mode is '" + scenario_.mode +
                          "'; expected lockstep or realtime (an external plant is a process of its own)");
    if (!(scenario_.publish_rate > 0.0) || !std::isfinite(scenario_.publish_rate))
      throw ContractError(
          format("plant.publish_rate is %g; expected a rate > 0 [Hz]", scenario_.publish_rate));
    if (options_.watchdog_periods && *options_.watchdog_periods < 1)
      throw ContractError(format("watchdog_periods must be a whole number of periods >= 1; got %d",
                                 *options_.watchdog_periods));
    if (options_.limits) options_.limits->check(joints_);
  }

  // -- receiving -------------------------------------------------------
  template <class Msg>
  bool accept(const lcm::ReceiveBuffer* rbuf, Msg& msg) {
    contract::Verdict v;
    try {
      v = bus_.receive(rbuf, msg);
    } catch (const std::exception&) {  // never through LCM's C frames
      v = contract::Verdict::kUndecodable;
    }
    if (v == contract::Verdict::kAccepted) return true;
    ++rejected_[contract::reasonOf(v)];
    return false;
  }

  void onStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    lagrange::status_t s;
    if (!accept(rbuf, s) || s.process == "plant") return;
    peers_[s.process] = {s.state, s.last_tick};
    if (s.process == "logger") logger_tick_ = std::max(logger_tick_.value_or(s.last_tick), s.last_tick);
  }

  void onActuatorState(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    lagrange::actuator_state_t a;
    if (!accept(rbuf, a)) return;
    if (a.header.publisher != "actuator") {
      ++rejected_["not the actuator's"];
      return;
    }
    if (a.num_joints != joints_ || a.torque_steps != 1 || a.tau_applied.size() != 1 ||
        static_cast<int>(a.tau_applied[0].size()) != joints_) {
      ++rejected_["wrong size"];
      return;
    }
    const std::vector<double>& tau = a.tau_applied[0];
    if (!std::all_of(tau.begin(), tau.end(), [](double x) { return std::isfinite(x); })) {
      ++rejected_["non-finite torque (NaN or Inf) from " + a.header.publisher];
      return;
    }
    const bool newest = !answers_.newestTick() || a.header.tick > *answers_.newestTick();
    answers_.take(a.header.tick, tau, a.header.publish_utime);
    // Realtime's end-to-end latency, as the built-in plant measures it: from
    // publishing a position to receiving the actuator state of its tick
    // (LCM's receive time, wall clock, against the run's clock).
    if (newest && a.header.tick >= 0) {
      const auto& [tick, utime] = published_[static_cast<size_t>(a.header.tick % kLatencyRing)];
      if (tick == a.header.tick)
        latencies_.add(static_cast<double>(std::max<int64_t>(0, rbuf->recv_utime - utime)) * 1e-6);
    }
  }

  void handle(int timeout_ms) { bus_.handle(timeout_ms); }

  // What has arrived, without waiting: kDrainLate datagrams whatever the
  // time -- a loop behind schedule must still read the actuator's newest
  // torque, or the torque goes stale while it sits on the socket --, then more
  // while before `until_ns` (CLOCK_MONOTONIC), at most kDrainMax: a flood of
  // forged ones, each refused by its MAC, must not hold the loop (the built-in
  // node's bound, transport/lcm_node.hpp).
  void drain(int64_t until_ns) {
    for (int handled = 0; handled < kDrainMax; ++handled)
      if ((handled >= kDrainLate && monotonicNs() >= until_ns) || bus_.handle(0) <= 0) return;
  }

  // -- the arm ---------------------------------------------------------
  void take(const PlantState& state, const std::string& what) {
    state.check(joints_, what);
    q_ = state.q;
    qdot_ = state.qdot;
    kinetic_ = state.kinetic_energy;
    potential_ = state.potential_energy;
  }

  std::vector<double> advance(int64_t k, const std::vector<double>& tau) {
    const double t = static_cast<double>(k) * period_;
    auto [u, clipped] = options_.limits ? options_.limits->clip(tau) : std::make_pair(tau, false);
    if (clipped) ++clipped_;
    const std::string what = format("step() at t = %.6g s", t);
    const int64_t began = monotonicNs();
    PlantState state = callUser([&] { return step_(t, u, period_); }, what);
    step_ns_ = monotonicNs() - began;  // the arm's share of the period, apart from ours
    take(state, what);
    return u;
  }

  // A crossed limit ends the run; brake() is servePlant's, as on every end but "finished".
  void checkLimits(int64_t k) {
    const auto why = options_.limits ? options_.limits->breach(q_, qdot_) : std::nullopt;
    if (!why) return;
    throw PlantStopped(format("%s at tick %lld (t = %.6g s); the plant stopped the run (its limits)",
                              why->c_str(), static_cast<long long>(k), static_cast<double>(k) * period_));
  }

  // The watchdog's brake (the arm's time does not wait), apart from the one of the end.
  void watchdogBrake() {
    if (options_.brake) callUser(options_.brake, "brake() (the watchdog)");
  }

  // -- publishing ------------------------------------------------------
  Sample sample(int64_t k, const std::vector<double>& tau, TorqueSource source, int64_t input_tick) const {
    Sample s;
    s.k = k;
    s.t = static_cast<double>(k) * period_;
    s.position.num_joints = joints_;
    s.position.q = q_;
    s.truth.num_joints = joints_;
    s.truth.q = q_;
    s.truth.qdot = qdot_;
    s.truth.tau_applied = tau;
    s.truth.kinetic_energy = kinetic_;
    s.truth.potential_energy = potential_;
    s.truth.total_energy = kinetic_ + potential_;
    s.truth.input_actuator_tick = input_tick;
    s.truth.torque_source = static_cast<int8_t>(source);
    return s;
  }

  void send(Sample& s, bool truth = true) {
    bus_.publish("PLANT_POSITION", s.position, s.k, s.t);
    auto& sent = published_[static_cast<size_t>(s.k % kLatencyRing)];
    if (sent.first != s.k)
      sent = {s.k, s.position.header.publish_utime};  // the first copy: what was answered
    if (truth) bus_.publish("PLANT_TRUTH", s.truth, s.k, s.t);
  }

  void status(const std::string& state, int64_t last_tick, const std::string& message = "",
              const lagrange::loop_stats_t& loop = {}) {
    publishStatus(bus_, period_, state, last_tick, message, loop);
  }

  // -- what went wrong -------------------------------------------------
  std::string heard() const {
    std::string peers, rejected;
    for (const auto& [process, last] : peers_)
      peers += (peers.empty() ? "" : ", ") + format("%s %s at tick %lld", process.c_str(), last.first.c_str(),
                                                    static_cast<long long>(last.second));
    for (const auto& [why, n] : rejected_)
      rejected +=
          (rejected.empty() ? "" : ", ") + format("%lld (%s)", static_cast<long long>(n), why.c_str());
    return "heard: " + (peers.empty() ? std::string("nobody") : peers) +
           "; rejected datagrams: " + (rejected.empty() ? std::string("none") : rejected);
  }

  PlantStopped stalled(const std::string& what, int64_t k, double waited) const {
    return PlantStopped(format("stalled at tick %lld: %s for %.1f s (lockstep.stall_timeout %g s); %s",
                               static_cast<long long>(k), what.c_str(), waited, scenario_.stall_timeout,
                               heard().c_str()));
  }

  std::string loggerTickText() const {
    return logger_tick_ ? format("STATUS last_tick %lld", static_cast<long long>(*logger_tick_))
                        : std::string("no STATUS from it yet");
  }

  int finish(std::string message, const lagrange::loop_stats_t& loop = {}) {
    if (clipped_ > 0) {
      message += format(" torque_clipped=%lld", static_cast<long long>(clipped_));
      warn(format("clipped the torque to its limits in %lld periods", static_cast<long long>(clipped_)));
    }
    for (int i = 0; i < 3; ++i) status("finished", last_tick_, message, loop);  // a datagram can be lost
    finished_ = true;
    return 0;
  }

  // -- lockstep --------------------------------------------------------
  bool loggerWithin(int64_t k) const { return logger_tick_ && k - *logger_tick_ <= scenario_.logger_window; }

  void forgetConfirmed() {
    if (logger_tick_) unconfirmed_.erase(unconfirmed_.begin(), unconfirmed_.upper_bound(*logger_tick_));
  }

  // The logger lacks what it has not confirmed: every retransmit_timeout, again.
  double resendForLogger(double now, double resend_at) {
    if (!logger_tick_ || now < resend_at) return resend_at;
    forgetConfirmed();
    for (auto& [tick, s] : unconfirmed_) {
      send(s);
      ++log_resends_;
    }
    return now + scenario_.retransmit_timeout;
  }

  // Until the logger is at most logger_window behind tick k; false: stopped.
  bool awaitLogger(int64_t k) {
    double wait_start = seconds(), resend_at = wait_start + scenario_.retransmit_timeout;
    bool resumed = false;
    while (!loggerWithin(k)) {
      if (stopRequested()) return false;
      if (takeResume()) {
        wait_start = seconds();
        resumed = true;
      }
      const double limit = logger_tick_ && !resumed ? scenario_.stall_timeout : startup_;
      if (seconds() - wait_start > limit)
        throw stalled("waited for the logger (" + loggerTickText() + ")", k, seconds() - wait_start);
      handle(5);
      resend_at = resendForLogger(seconds(), resend_at);
    }
    return true;
  }

  // Until the actuator answers tick k, its position re-sent every
  // retransmit_timeout; false: stopped.
  bool awaitAnswer(int64_t k, Sample& s, double published) {
    double deadline = published + (k == 0 ? startup_ : scenario_.stall_timeout);
    double resend = published + scenario_.retransmit_timeout;
    while (!answers_.answered()) {
      if (stopRequested()) return false;
      const double now = seconds();
      if (takeResume()) deadline = std::max(deadline, now + startup_);
      if (now > deadline)
        throw stalled(format("no ACTUATOR_STATE of tick %lld", static_cast<long long>(k)), k,
                      now - published);
      handle(5);
      if (!answers_.answered() && seconds() >= resend) {
        send(s, false);
        ++retransmits_;
        resend = seconds() + scenario_.retransmit_timeout;
      }
    }
    return true;
  }

  // The end: every sample in the log first (bounded by stall_timeout).
  void awaitLoggerEnd() {
    const double deadline = seconds() + scenario_.stall_timeout;
    double resend_at = seconds() + scenario_.retransmit_timeout;
    while ((!logger_tick_ || *logger_tick_ < last_tick_) && seconds() < deadline && !stopRequested()) {
      handle(5);
      resend_at = resendForLogger(seconds(), resend_at);
    }
    if (!logger_tick_ || *logger_tick_ < last_tick_)
      warn(format("warning: the logger confirmed every message up to tick %s of %lld",
                  logger_tick_ ? std::to_string(*logger_tick_).c_str() : "none",
                  static_cast<long long>(last_tick_)));
  }

  int serveLockstep() {
    status("ready", -1);
    // Waiting is lockstep's protocol: an answer late by scheduling is no
    // silence of the controller's, and a brake there would be one the summary
    // never counts. lockstep.stall_timeout ends a run that stalls.
    if (options_.watchdog_periods)
      warn(
          format("watchdog_periods=%d applies in realtime only; in lockstep the plant waits for each answer "
                 "(lockstep.stall_timeout %g s ends a stalled run)",
                 *options_.watchdog_periods, scenario_.stall_timeout));
    std::vector<double> tau(static_cast<size_t>(joints_), 0.0);
    TorqueSource source = TorqueSource::kZero;
    int64_t input_tick = -1;
    double next_status = seconds();
    for (int64_t k = 0; k <= last_tick_; ++k) {
      if (!awaitLogger(k)) {
        status("interrupted", k - 1);
        return 0;
      }
      Sample& s = unconfirmed_[k] = sample(k, tau, source, input_tick);
      answers_.await(k);
      send(s);
      const double published = seconds();
      if (published >= next_status) {
        status("running", k);
        next_status = published + 0.5;
      }
      if (!awaitAnswer(k, s, published)) {
        status("interrupted", k);
        return 0;
      }
      forgetConfirmed();  // after the wait: s stays valid while it is re-sent
      if (k < last_tick_) {
        tau = advance(k, answers_.answer());  // the awaited tick's first answer
        source = TorqueSource::kCommanded;
        input_tick = k;
        checkLimits(k + 1);
      }
    }
    awaitLoggerEnd();
    return finish(format("retransmits=%lld log_resends=%lld", static_cast<long long>(retransmits_),
                         static_cast<long long>(log_resends_)));
  }

  // -- realtime --------------------------------------------------------
  struct LoopClock {
    int64_t period_ns = 0, t0 = 0;  // deadline k: t0 + k period_ns [ns of CLOCK_MONOTONIC]
    Lateness lateness;
    int64_t misses = 0, miss_run = 0, longest = 0;
    Lateness ages;           // how old each torque was when first applied [s]
    int64_t used_tick = -1;  // the newest ACTUATOR_STATE tick applied
    int64_t missing = 0;     // periods without a torque newer than used_tick (the built-in's count)
    int64_t sent = 0;        // ticks published
  };

  // Deadlines on whole periods of CLOCK_MONOTONIC, as the built-in loops'
  // (transport/rate_loop.cpp): the actuator wakes half a period after each,
  // when the controller has answered, and takes only a fresh command.
  LoopClock startClock() const {
    LoopClock c;
    c.period_ns = std::llround(1e9 / scenario_.publish_rate);
    c.t0 = (monotonicNs() / c.period_ns + 1) * c.period_ns;
    return c;
  }

  // Sleeps to tick k's deadline (absolute: no drift), or counts a miss when
  // it has passed; records how late it woke.
  void waitForTick(LoopClock& c, int64_t k) const {
    const int64_t deadline = c.t0 + k * c.period_ns;
    if (monotonicNs() > deadline) {
      ++c.misses;
      c.longest = std::max(c.longest, ++c.miss_run);
    } else {
      c.miss_run = 0;
      const timespec at{static_cast<time_t>(deadline / 1000000000LL),
                        static_cast<long>(deadline % 1000000000LL)};
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &at, nullptr) == EINTR && !stopRequested()) {
      }
    }
    c.lateness.add(static_cast<double>(std::max<int64_t>(0, monotonicNs() - deadline)) * 1e-9);
  }

  lagrange::loop_stats_t loopStats(const LoopClock& c) const {
    lagrange::loop_stats_t st{};
    st.period = period_;
    st.scheduler = schedulerNow();
    const int64_t cycles = c.sent;
    st.cycles = cycles;
    const double elapsed = static_cast<double>(monotonicNs() - c.t0) * 1e-9;
    st.achieved_rate = elapsed > 0.0 ? static_cast<double>(cycles) / elapsed : 0.0;
    st.jitter_p50 = c.lateness.percentile(0.5);
    st.jitter_p99 = c.lateness.percentile(0.99);
    st.jitter_max = c.lateness.max();
    st.deadline_misses = c.misses;
    st.longest_miss_run = c.longest;
    st.input_age_p50 = c.ages.percentile(0.5);
    st.input_age_p99 = c.ages.percentile(0.99);
    st.input_age_max = c.ages.max();
    st.missing_inputs = c.missing;
    st.torque_held = choice_.held();
    st.torque_zeroed = choice_.zeroed();
    st.stale_inputs = choice_.held() + choice_.zeroed();
    st.latency_p50 = latencies_.percentile(0.5);
    st.latency_p99 = latencies_.percentile(0.99);
    st.latency_max = latencies_.max();
    return st;
  }

  bool heardEveryPeer() const {
    return peers_.count("logger") && peers_.count("controller") && peers_.count("actuator");
  }

  // A realtime plant starts its clock once every process has spoken; false: stopped.
  bool awaitPeers() {
    const double start = seconds();
    while (!heardEveryPeer()) {
      if (stopRequested()) return false;
      if (seconds() - start > startup_)
        throw stalled("waited for STATUS from logger, controller and actuator", 0, seconds() - start);
      handle(20);
    }
    return true;
  }

  // The torque over the period after tick k, by the scenario's stale-torque policy and the watchdog.
  TorqueChoice::Choice chooseTorque(int64_t k) {
    const std::optional<int64_t> newest_tick = answers_.newestTick();
    TorqueChoice::Choice c = choice_.choose(k, newest_tick, answers_.newestTorque(), joints_);
    if (c.tripped_now) {
      const std::string newest =
          newest_tick ? format("the newest torque (tick %lld)", static_cast<long long>(*newest_tick))
                      : std::string("no torque yet");
      warn(format(
          "watchdog: %s is more than %d periods old at tick %lld (t = %.6g s); commanding zero torque%s",
          newest.c_str(), *choice_.watchdogPeriods(), static_cast<long long>(k),
          static_cast<double>(k) * period_, options_.brake ? " and braking" : ""));
      watchdogBrake();
    }
    return c;
  }

  // A commanded torque's age when first applied: from its publication to now, on the run's clock.
  void noteAge(LoopClock& c, const TorqueChoice::Choice& chosen) const {
    if (chosen.source != TorqueSource::kCommanded || chosen.input_tick <= c.used_tick) return;
    c.used_tick = chosen.input_tick;
    c.ages.add(static_cast<double>(std::max<int64_t>(0, bus_.utime() - answers_.newestUtime())) * 1e-6);
  }

  // plant.log's line on what a period cost: whether a rate can be held is
  // step()'s time plus the helper's (bench/python_helper_cost.sh reads it).
  void sayCost() const {
    if (own_cost_.count() == 0) return;
    warn(
        format("per period: this helper %.3f ms (median; 99 %%: %.3f ms), step() %.3f ms (median; 99 %%: "
               "%.3f ms); the period %.3f ms",
               own_cost_.percentile(0.5) * 1e3, own_cost_.percentile(0.99) * 1e3,
               step_cost_.percentile(0.5) * 1e3, step_cost_.percentile(0.99) * 1e3, period_ * 1e3));
  }

  int serveRealtime() {
    status("ready", -1);
    if (!awaitPeers()) {
      status("interrupted", -1);
      return 0;
    }
    // The kernel's default 50 us timer slack would be 50 us of jitter on every wake-up.
    prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
    LoopClock clock = startClock();
    int64_t next_status = clock.t0 + 500000000LL;
    std::vector<double> tau(static_cast<size_t>(joints_), 0.0);
    TorqueSource source = TorqueSource::kZero;
    int64_t input_tick = -1;
    for (int64_t k = 0; k <= last_tick_; ++k) {
      if (stopRequested()) break;
      waitForTick(clock, k);
      const int64_t woke = monotonicNs();
      Sample s = sample(k, tau, source, input_tick);
      send(s);
      ++clock.sent;
      if (k == last_tick_) break;
      drain(clock.t0 + (k + 1) * clock.period_ns);  // never past the next tick's deadline
      const std::optional<int64_t> newest_tick = answers_.newestTick();
      if (!newest_tick || *newest_tick <= clock.used_tick) ++clock.missing;
      const TorqueChoice::Choice chosen = chooseTorque(k);
      noteAge(clock, chosen);
      tau = advance(k, chosen.tau);
      source = chosen.source;
      input_tick = chosen.input_tick;
      checkLimits(k + 1);
      if (monotonicNs() >= next_status) {
        status("running", k, "", loopStats(clock));
        next_status += 500000000LL;
      }
      step_cost_.add(static_cast<double>(step_ns_) * 1e-9);
      own_cost_.add(static_cast<double>(monotonicNs() - woke - step_ns_) * 1e-9);
    }
    const lagrange::loop_stats_t loop = loopStats(clock);
    sayCost();
    if (stopRequested()) {
      status("interrupted", clock.used_tick, "", loop);  // as the built-in plant: the torque's tick
      return 0;
    }
    if (choice_.held() + choice_.zeroed() > 0)
      warn(format("warning: stale torque: held %lld periods, zeroed %lld periods",
                  static_cast<long long>(choice_.held()), static_cast<long long>(choice_.zeroed())));
    std::string message =
        format("torque_held=%lld torque_zeroed=%lld", static_cast<long long>(choice_.held()),
               static_cast<long long>(choice_.zeroed()));
    if (choice_.watchdogTrips() > 0)
      message += format(" watchdog_trips=%lld", static_cast<long long>(choice_.watchdogTrips()));
    return finish(message, loop);
  }

  contract::Bus& bus_;
  PlantStep step_;
  PlantOptions options_;
  PlantScenario scenario_;
  int joints_;
  double period_;
  int64_t last_tick_;
  double startup_;
  TorqueChoice choice_;
  std::vector<double> q_, qdot_;
  double kinetic_ = std::numeric_limits<double>::quiet_NaN();  // [J]; NaN: not known
  double potential_ = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, std::pair<std::string, int64_t>>
      peers_;                                // process -> (state, last_tick) of its newest STATUS
  std::optional<int64_t> logger_tick_;       // none: the logger not heard yet
  ActuatorAnswers answers_;                  // lockstep's answer, realtime's newest
  std::map<std::string, int64_t> rejected_;  // why -> datagrams dropped
  std::map<int64_t, Sample> unconfirmed_;    // lockstep: until the logger confirms them
  int64_t retransmits_ = 0, log_resends_ = 0, clipped_ = 0;
  // (tick, publish_utime) of each tick's first position; tick -1: none yet.
  std::vector<std::pair<int64_t, int64_t>> published_ =
      std::vector<std::pair<int64_t, int64_t>>(kLatencyRing, {-1, 0});
  Lateness latencies_;             // realtime: position published -> its actuator state received [s]
  int64_t step_ns_ = 0;            // how long the last step() took
  Lateness own_cost_, step_cost_;  // realtime: a period's time besides step(), and step()'s [s]
  bool finished_ = false;          // STATUS "finished" sent: the one end without brake()
};

}  // namespace

int servePlant(const PlantStep& step, const PlantOptions& options,
               const std::function<PlantScenario()>& read_scenario) {
  // Installed first and kept to the end: a SIGTERM while brake() runs is noted, not fatal.
  SignalScope signals;
  std::unique_ptr<contract::Bus> bus;
  double period = 0.0;
  bool braked = false;
  // Every end but "finished": brake() once, when given -- the bridge's own way
  // to make the arm safe. What it threw, if it did.
  const auto safe_stop = [&]() -> std::optional<std::string> {
    if (!options.brake || braked) return std::nullopt;
    braked = true;
    std::cerr << "plant: calling brake()" << std::endl;
    try {
      callUser(options.brake, "brake()");
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::nullopt;
  };
  // Said on stderr, the arm made safe, and the run told why (STATUS "failed").
  const auto fail = [&](const std::string& why) {
    std::cerr << program_invocation_short_name << ": " << why << std::endl;
    if (const auto brake_error = safe_stop())
      std::cerr << program_invocation_short_name << ": " << *brake_error << std::endl;
    if (bus) {
      try {
        publishStatus(*bus, period, "failed", -1, why.empty() ? std::string("failed") : why.substr(0, 500),
                      {});
      } catch (const std::exception&) {  // LCM itself failing: stderr has said it
      }
    }
    return 1;
  };
  try {
    bus = std::make_unique<contract::Bus>("plant");
    const PlantScenario s = read_scenario();
    period = s.publish_rate > 0.0 ? 1.0 / s.publish_rate : 0.0;
    Plant plant(*bus, step, options, s);
    const int code = plant.serve();
    if (!plant.finished()) {  // interrupted (SIGTERM, SIGINT): the arm is left safe too
      if (const auto brake_error = safe_stop()) return fail(*brake_error);
    }
    return code;
  } catch (const std::exception& e) {
    return fail(e.what());
  } catch (...) {
    return fail("an exception that is not a std::exception");
  }
}

}  // namespace lagrange::sdk
