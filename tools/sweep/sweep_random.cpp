#include "tools/sweep/sweep_random.hpp"

#include <cmath>

#include "util/splitmix.hpp"

namespace lagrange::tools {

namespace {

using util::splitmix64;

std::uint64_t bits(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return splitmix64(splitmix64(splitmix64(seed) ^ stream) ^ index);
}

double toUnit(std::uint64_t b) { return util::unitInterval(b); }

}  // namespace

double uniform01(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return toUnit(bits(seed, stream, index));
}

Eigen::VectorXd unitDirection(std::uint64_t seed, std::uint64_t stream, std::uint64_t index, int n) {
  constexpr double kTwoPi = 6.283185307179586;
  Eigen::VectorXd v(n);
  std::uint64_t draw = 0;
  do {  // a zero vector has probability 0; draw again rather than divide by it
    for (int i = 0; i < n; i += 2) {
      const std::uint64_t b = bits(seed, stream, index * 0x10000ULL + draw++);
      const double u1 = 1.0 - toUnit(b);  // (0, 1]: log is finite
      const double u2 = toUnit(splitmix64(b));
      const double r = std::sqrt(-2.0 * std::log(u1));
      v[i] = r * std::cos(kTwoPi * u2);
      if (i + 1 < n) v[i + 1] = r * std::sin(kTwoPi * u2);
    }
  } while (v.norm() == 0.0);
  return v / v.norm();
}

HaltonSequence::HaltonSequence(int dims, std::uint64_t seed) {
  for (int p = 2; static_cast<int>(bases_.size()) < dims; ++p) {
    bool prime = true;
    for (int d = 2; d * d <= p; ++d) prime = prime && p % d != 0;
    if (prime) bases_.push_back(p);
  }
  for (int d = 0; d < dims; ++d) shifts_.push_back(uniform01(seed, 0x3000, static_cast<std::uint64_t>(d)));
}

double HaltonSequence::at(long index, int dim) const {
  const int base = bases_.at(static_cast<size_t>(dim));
  double f = 1.0, r = 0.0;
  for (long i = index + 1; i > 0; i /= base) {  // index + 1: the sequence's 0 is a corner
    f /= base;
    r += f * static_cast<double>(i % base);
  }
  r += shifts_[static_cast<size_t>(dim)];
  return r - std::floor(r);
}

}  // namespace lagrange::tools
