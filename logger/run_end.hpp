#pragma once
/// @file
/// When the logger stops recording, without LCM or clock: once the plant has
/// reported "finished" and so have the controller and the actuator, or a
/// grace period after the plant finished -- or, since the plant's final
/// STATUS can be lost like any datagram, a grace period after every tick of
/// the run was confirmed. And when the plant has gone: a run spread over
/// hosts whose plant's host died leaves nobody to stop the logger, so
/// silence from the plant past a limit is an end too (a failed one).

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <string>

#include "transport/process_state.hpp"

namespace lagrange::logger {

class RunEnd {
 public:
  using Clock = std::chrono::steady_clock;

  /// @param start when the logger started listening: the plant's silence counts from there.
  RunEnd(Clock::duration grace, Clock::time_point start) : grace_(grace), plant_heard_at_(start) {}

  using State = transport::ProcessState;

  /// The state in a STATUS of `process`, received at `now`.
  void processState(const std::string& process, State state, Clock::time_point now) {
    states_[process] = state;
    if (process == "plant" && state == State::kFinished && !plant_finished_at_) plant_finished_at_ = now;
  }

  /// A message of the plant (any channel) received at `now`.
  void plantHeard(Clock::time_point now) {
    plant_heard_at_ = std::max(plant_heard_at_, now);
    plant_ever_heard_ = true;
  }
  /// How long the plant has been silent at `now`, when that is longer than
  /// `limit` (`start_limit` before it was first heard: it loads and checks
  /// its gains first) and it has not finished; else nothing.
  std::optional<Clock::duration> plantGone(Clock::time_point now, Clock::duration limit,
                                           Clock::duration start_limit) const {
    if (plant_finished_at_ || now - plant_heard_at_ <= (plant_ever_heard_ ? limit : start_limit))
      return std::nullopt;
    return now - plant_heard_at_;
  }
  bool plantEverHeard() const { return plant_ever_heard_; }

  /// True when plant, controller and actuator have all reported `state`.
  bool allReported(State state) const {
    return allOthers([state](State reported) { return reported == state; });
  }
  /// True when plant, controller and actuator have all reported an end (finished or interrupted).
  bool allEnded() const {
    return allOthers([](State reported) {
      return reported == State::kFinished || reported == State::kInterrupted || reported == State::kFailed;
    });
  }

  /// Whether to stop recording at `now`; `every_tick_confirmed` says whether
  /// the confirmed tick has reached the run's last.
  bool due(Clock::time_point now, bool every_tick_confirmed) {
    if (plant_finished_at_ && (allReported(State::kFinished) || now - *plant_finished_at_ > grace_))
      return true;
    if (!every_tick_confirmed) return false;
    if (!all_ticks_at_) all_ticks_at_ = now;
    return now - *all_ticks_at_ > grace_;
  }

 private:
  template <class Predicate>
  bool allOthers(Predicate holds) const {
    for (const char* process : {"plant", "controller", "actuator"}) {
      const auto it = states_.find(process);
      if (it == states_.end() || !holds(it->second)) return false;
    }
    return true;
  }

  Clock::duration grace_;
  std::map<std::string, State> states_;
  std::optional<Clock::time_point> plant_finished_at_, all_ticks_at_;
  Clock::time_point plant_heard_at_;
  bool plant_ever_heard_ = false;
};

}  // namespace lagrange::logger
