#pragma once
/// @file
/// The plant's side of lockstep (DESIGN section 4) as a state machine without
/// clock or LCM: the process loop (plant_loops.cpp) feeds it what arrives and
/// the time, and does what it answers. Three rules:
///
/// - the window: tick k goes out only once the logger has been heard and has
///   confirmed (STATUS last_tick) a tick no more than logger_window before k;
/// - the answer: the first ACTUATOR_STATE of the awaited tick is its answer;
///   a stale one (another tick) or a repeat is ignored; until it arrives the
///   tick's measurements are re-sent every retransmit_timeout;
/// - the log: the ticks the logger has not confirmed are kept (at most the
///   window) and re-sent every retransmit_timeout while the plant waits for
///   the logger, so a datagram lost on the way to the log is sent again.
///
/// `Sent` is what the loop published for a tick (its messages); tests use
/// anything copyable.

#include <chrono>
#include <cstdint>
#include <map>
#include <vector>

namespace lagrange::plant {

template <class Sent>
class LockstepProtocol {
 public:
  using Clock = std::chrono::steady_clock;

  struct Settings {
    int64_t last_tick = 0;         ///< the run's last tick
    int logger_window = 0;         ///< lockstep.logger_window
    Clock::duration retransmit{};  ///< lockstep.retransmit_timeout
  };

  explicit LockstepProtocol(const Settings& settings) : settings_(settings) {}

  // ---- what arrives ----
  /// The logger's STATUS last_tick: every message of every tick up to it is in the log.
  void loggerConfirmed(int64_t tick) {
    logger_tick_ = logger_heard_ ? std::max(logger_tick_, tick) : tick;
    logger_heard_ = true;
  }
  /// An ACTUATOR_STATE of `tick`: true when it answers the awaited tick for
  /// the first time (its torque is the one to apply), false when it is stale
  /// or a repeat.
  bool actuatorState(int64_t tick) {
    if (tick != awaited_ || answered_) return false;
    answered_ = true;
    return true;
  }

  // ---- waiting for the logger before tick k ----
  bool loggerHeard() const { return logger_heard_; }
  /// Whether tick k may go out: the logger is heard and at most the window behind.
  bool mayPublish(int64_t k) const { return logger_heard_ && k - logger_tick_ <= settings_.logger_window; }
  /// Starts waiting for the logger (arms the timer of the log re-sends).
  void awaitLogger(Clock::time_point now) { log_resend_at_ = now + settings_.retransmit; }
  /// The unconfirmed ticks to re-send now, oldest first: all of them when the
  /// timer has run out (and the logger is heard), none otherwise. Counted in logResends().
  std::vector<const Sent*> logResendsDue(Clock::time_point now) {
    std::vector<const Sent*> due;
    if (!logger_heard_ || now < log_resend_at_) return due;
    dropConfirmed();
    for (const auto& entry : unconfirmed_) due.push_back(&entry.second);
    log_resends_ += static_cast<long long>(due.size());
    log_resend_at_ = now + settings_.retransmit;
    return due;
  }

  // ---- tick k out, its answer awaited ----
  /// Tick k's messages went out at `now`: keep them for the logger and await the answer.
  void published(int64_t k, const Sent& sent, Clock::time_point now) {
    unconfirmed_.emplace(k, sent);
    dropConfirmed();  // bounded by the window
    awaited_ = k;
    answered_ = false;
    position_resend_at_ = now + settings_.retransmit;
  }
  bool answered() const { return answered_; }
  /// True when the awaited tick's measurements are to be re-sent now
  /// (unanswered for retransmit_timeout). Counted in retransmits().
  bool positionResendDue(Clock::time_point now) {
    if (answered_ || now < position_resend_at_) return false;
    ++retransmits_;
    position_resend_at_ = now + settings_.retransmit;
    return true;
  }

  // ---- the end ----
  bool allConfirmed() const { return logger_heard_ && logger_tick_ >= settings_.last_tick; }
  /// The logger's confirmed tick (-1 before it confirmed tick 0 or was heard).
  int64_t loggerTick() const { return logger_heard_ ? logger_tick_ : -1; }
  long long retransmits() const { return retransmits_; }
  long long logResends() const { return log_resends_; }
  size_t unconfirmedTicks() const { return unconfirmed_.size(); }

 private:
  void dropConfirmed() {
    if (logger_heard_) unconfirmed_.erase(unconfirmed_.begin(), unconfirmed_.upper_bound(logger_tick_));
  }

  Settings settings_;
  bool logger_heard_ = false;
  int64_t logger_tick_ = -1;
  int64_t awaited_ = -1;
  bool answered_ = false;
  std::map<int64_t, Sent> unconfirmed_;
  Clock::time_point log_resend_at_{}, position_resend_at_{};
  long long retransmits_ = 0, log_resends_ = 0;
};

}  // namespace lagrange::plant
