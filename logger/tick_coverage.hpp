#pragma once
/// @file
/// Which ticks of one channel reached the log intact, so the summary can say
/// how many of the run's ticks have none (summary.json log.missing_ticks).

#include <cstdint>
#include <vector>

namespace lagrange::logger {

class TickCoverage {
 public:
  /// Ticks beyond `last_tick` (the run's last) are ignored: a forged or
  /// corrupt tick must not make the logger allocate for it.
  explicit TickCoverage(int64_t last_tick) : seen_(static_cast<size_t>(last_tick < 0 ? 0 : last_tick + 1)) {}

  void add(int64_t tick) {
    if (tick >= 0 && static_cast<size_t>(tick) < seen_.size()) seen_[static_cast<size_t>(tick)] = true;
    while (next_ < seen_.size() && seen_[next_]) ++next_;
  }

  /// The newest tick up to which every tick has a message (-1: not tick 0).
  int64_t contiguousThrough() const { return static_cast<int64_t>(next_) - 1; }

  /// Ticks 0..up_to (clamped to the run) without a message.
  long long missingUpTo(int64_t up_to) const {
    long long missing = 0;
    for (int64_t k = 0; k <= up_to && static_cast<size_t>(k) < seen_.size(); ++k)
      missing += seen_[static_cast<size_t>(k)] ? 0 : 1;
    return missing;
  }

 private:
  std::vector<bool> seen_;
  size_t next_ = 0;  ///< the oldest tick without a message
};

}  // namespace lagrange::logger
