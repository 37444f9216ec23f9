#pragma once
/// @file
/// The median the benchmarks quote (the upper one of an even count).

#include <algorithm>
#include <vector>

namespace lagrange::bench {

inline double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace lagrange::bench
