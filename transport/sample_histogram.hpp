#pragma once
/// @file
/// Percentiles of a stream of durations without keeping the samples: a fixed
/// set of log-spaced bins, 1 % wide, from 10 ns to 100 s, allocated once.
/// Adding a sample is O(1) and allocates nothing, so a realtime loop records
/// every cycle of an hours-long run on its own thread; reading the
/// percentiles walks the bins (about 2 300), instead of sorting a whole
/// run's samples every half second as the loops once did. p50 and p99 are
/// the upper edge of the bin that holds the quantile: at most 1 % above the
/// exact order statistic, and never above the largest sample, which is exact.

#include <array>
#include <cstdint>

namespace lagrange::transport {

/// Median, 99th percentile and maximum of a sample (zeros when empty).
struct Percentiles {
  double p50 = 0.0, p99 = 0.0, max = 0.0;
};

class SampleHistogram {
 public:
  static constexpr double kLowest = 1e-8;                      ///< [s]: the first bin's upper edge
  static constexpr int kBinsPerDecade = 232;                   ///< 10^(1/232) = 1.0100: 1 % wide
  static constexpr int kDecades = 10;                          ///< up to 1e-8 * 1e10 = 100 s
  static constexpr int kBins = kBinsPerDecade * kDecades + 2;  ///< + zero, + overflow

  /// A duration [s]: <= 0 in the zero bin, above 100 s in the last.
  void add(double seconds);
  Percentiles percentiles() const;
  int64_t count() const { return count_; }

 private:
  double upperEdge(int bin) const;
  std::array<int64_t, kBins> bins_{};
  int64_t count_ = 0;
  double max_ = 0.0;
};

}  // namespace lagrange::transport
