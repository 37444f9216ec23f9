#include "transport/sample_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace lagrange::transport {

void SampleHistogram::add(double seconds) {
  if (!(seconds > 0)) seconds = 0.0;  // zero, negative (a clock skew) and NaN: the zero bin
  int bin = 0;
  if (seconds > 0) {
    const double decades = std::log10(seconds / kLowest);
    bin = decades <= 0 ? 1 : 1 + static_cast<int>(std::ceil(decades * kBinsPerDecade));
    bin = std::min(bin, kBins - 1);
  }
  ++bins_[static_cast<size_t>(bin)];
  max_ = count_ == 0 ? std::max(seconds, 0.0) : std::max(max_, seconds);
  ++count_;
}

double SampleHistogram::upperEdge(int bin) const {
  if (bin == 0) return 0.0;
  if (bin == kBins - 1) return max_;
  return kLowest * std::pow(10.0, static_cast<double>(bin - 1) / kBinsPerDecade);
}

Percentiles SampleHistogram::percentiles() const {
  Percentiles p;
  if (count_ == 0) return p;
  // The same order statistic as sorting would give: index ceil(q n) - 1.
  const auto at = [&](double q) {
    const int64_t index =
        std::max<int64_t>(0, static_cast<int64_t>(std::ceil(q * static_cast<double>(count_))) - 1);
    int64_t seen = 0;
    for (int b = 0; b < kBins; ++b) {
      seen += bins_[static_cast<size_t>(b)];
      if (seen > index) return std::min(upperEdge(b), max_);
    }
    return max_;
  };
  p.p50 = at(0.5);
  p.p99 = at(0.99);
  p.max = max_;
  return p;
}

}  // namespace lagrange::transport
