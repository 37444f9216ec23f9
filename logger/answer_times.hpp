#pragma once
/// @file
/// How long each process took to answer, tick by tick, as the logger hears
/// it: the controller answers the plant's position of tick k with its
/// command of tick k, the actuator that command with its state of tick k,
/// and in lockstep the plant that state with its position of tick k + 1
/// (a plant that takes seconds a step is named as a slow controller is).
/// The logger hears every channel, so this holds for a program from outside
/// (an external controller reports nothing itself) as for the built-in ones.
/// A wait longer than `supervision.slow_answer` is said while it lasts --
/// a controller taking 5 s a sample would otherwise sit silent for hours --
/// and the median and worst answer go into summary.json (`answers`).
/// Pure: the caller gives arrival times, nothing here reads a clock.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "transport/sample_histogram.hpp"

namespace lagrange::logger {

class AnswerTimes {
 public:
  /// One who answers: `name` (controller, actuator, plant) answers
  /// `question` (a channel) of tick k with `answer` of tick k +
  /// `tick_offset` (the plant: 1); `program` names it.
  struct Answerer {
    std::string name;
    std::string program;
    std::string question;
    std::string answer;
    int64_t tick_offset = 0;
  };
  /// A wait past the threshold, to say while it lasts.
  struct Slow {
    std::string name;
    std::string program;
    int64_t tick = 0;
    double waited = 0.0;  ///< [s] so far
  };

  AnswerTimes(std::vector<Answerer> answerers, double threshold);

  /// The first copy of `channel`'s message of `tick` arrived at `t` [s].
  /// Copies after the first (re-sent, duplicated) change nothing.
  void arrived(const std::string& channel, int64_t tick, double t);
  /// The waits that passed the threshold by `now` and were not said yet:
  /// at most one per answerer and tick; then at most one every
  /// `repeat_every` seconds per answerer (the count is in the summary).
  std::vector<Slow> newlySlow(double now, double repeat_every = 10.0);
  /// {threshold, NAME: {program, answered, median, worst, worst_tick, slow}}:
  /// answer times [s] of the ticks answered -- the median (the lower one of
  /// an even count) from 1 %-wide bins (at most 1 % above the exact one: a run of hours at 1 kHz keeps no
  /// per-tick list in the logger's locked memory), the worst exact; null
  /// median/worst when none.
  nlohmann::json summary() const;

 private:
  struct Record {
    Answerer who;
    std::map<int64_t, double> asked;   ///< tick -> when the question came, until answered
    transport::SampleHistogram times;  ///< answer times [s]
    double worst = 0.0;
    int64_t worst_tick = -1;
    long long slow = 0;          ///< answers slower than the threshold
    int64_t answered_tick = -1;  ///< the newest tick answered
    int64_t said_tick = -1;      ///< the newest tick whose wait was said
    double said_at = -1.0e300;   ///< when the last line was said [s]
  };
  std::vector<Record> records_;
  double threshold_;
};

}  // namespace lagrange::logger
