#pragma once
/// @file
/// SplitMix64: the project's portable random numbers (std:: distributions
/// differ between C++ libraries, and seeded results must not). The mixing
/// function for counter-based draws (tools/sweep/sweep_random.hpp), and a
/// sequential stream for a few seeded draws (model error, the sampled-data
/// check's seeded states).

#include <cmath>
#include <cstdint>

namespace lagrange::util {

/// SplitMix64's output for state x (its increment added, then mixed).
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// 53 random bits of b as a double in [0, 1).
inline double unitInterval(std::uint64_t b) { return static_cast<double>(b >> 11) * 0x1.0p-53; }

/// Draws in sequence from a seed.
class SplitMix64Stream {
 public:
  explicit SplitMix64Stream(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    const std::uint64_t out = splitmix64(state_);
    state_ += 0x9E3779B97F4A7C15ULL;
    return out;
  }
  /// Uniform in [-1, 1).
  double symmetric() { return unitInterval(next()) * 2.0 - 1.0; }
  /// Standard normal (Box-Muller, the cosine branch).
  double gaussian() {
    const double u1 = (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53;  // (0, 1): log is finite
    const double u2 = unitInterval(next());
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::uint64_t state_;
};

}  // namespace lagrange::util
