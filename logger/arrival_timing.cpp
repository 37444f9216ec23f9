#include "logger/arrival_timing.hpp"

#include <algorithm>
#include <cmath>

namespace lagrange::logger {

void ArrivalTiming::arrived(int64_t tick, double t) {
  if (!heard_.insert(tick).second) return;
  if (heard_.size() > 4096) heard_.erase(heard_.begin());  // only recent ticks can come again
  if (arrivals_ > 0) {
    const double interval = t - last_;
    jitter_.add(std::abs(interval - period_));
    // The periods that passed without a message: a gap of 3 periods missed 2.
    const int64_t missed = std::max<int64_t>(0, std::llround(interval / period_) - 1);
    // Every gap ends with an arrival: the periods missed in a row are one gap's.
    misses_ += missed;
    longest_miss_run_ = std::max(longest_miss_run_, missed);
  } else {
    first_ = t;
  }
  last_ = t;
  ++arrivals_;
}

nlohmann::json ArrivalTiming::loopJson() const {
  if (arrivals_ < 2) return nullptr;
  const transport::Percentiles j = jitter_.percentiles();
  const int64_t intervals = arrivals_ - 1;
  return {{"period", period_},
          {"scheduler", "unknown"},
          {"cycles", arrivals_},
          {"achieved_rate", last_ > first_ ? nlohmann::json(static_cast<double>(intervals) / (last_ - first_))
                                           : nlohmann::json()},  // not measured: null, never 0
          {"jitter", {{"p50", j.p50}, {"p99", j.p99}, {"max", j.max}}},
          {"deadline_misses", misses_},
          {"on_time_fraction", static_cast<double>(arrivals_) / static_cast<double>(arrivals_ + misses_)},
          {"longest_miss_run", longest_miss_run_},
          {"measured_by",
           "the logger, from the arrivals of CONTROL_COMMAND: a program from outside reports no loop of its "
           "own"}};
}

}  // namespace lagrange::logger
