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
    if (interval > 1.5 * period_) {
      ++misses_;
      longest_miss_run_ = std::max(longest_miss_run_, ++miss_run_);
    } else {
      miss_run_ = 0;
    }
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
          {"achieved_rate", last_ > first_ ? static_cast<double>(intervals) / (last_ - first_) : 0.0},
          {"jitter", {{"p50", j.p50}, {"p99", j.p99}, {"max", j.max}}},
          {"deadline_misses", misses_},
          {"on_time_fraction", 1.0 - static_cast<double>(misses_) / static_cast<double>(intervals)},
          {"longest_miss_run", longest_miss_run_},
          {"measured_by",
           "the logger, from the arrivals of CONTROL_COMMAND: a program from outside reports no loop of its "
           "own"}};
}

}  // namespace lagrange::logger
