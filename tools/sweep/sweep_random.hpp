#pragma once
/// @file
/// The sweep's random numbers: counter-based (splitmix64 of the seed, a
/// stream and an index), so a row's draws depend on nothing but the sweep's
/// seed and the row -- not on the order rows run in or on how they are split
/// among shards -- and are the same with any C++ library (no std::
/// distribution, whose algorithms the standard leaves to each library).

#include <Eigen/Dense>
#include <cstdint>
#include <vector>

namespace lagrange::tools {

/// Streams: one per axis for the design's draws, one per axis for directions.
inline constexpr std::uint64_t kStreamDesign = 0x1000;
inline constexpr std::uint64_t kStreamDirection = 0x2000;

/// A uniform double in [0, 1), 53 random bits.
double uniform01(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

/// A unit vector of dimension n, uniform on the sphere (normalised Gaussians,
/// Box-Muller); draw `index` of `stream`.
Eigen::VectorXd unitDirection(std::uint64_t seed, std::uint64_t stream, std::uint64_t index, int n);

/// The Halton sequence in `dims` dimensions (bases 2, 3, 5, ...), shifted
/// modulo 1 by a seeded random vector (a Cranley-Patterson rotation): a
/// low-discrepancy design that differs from seed to seed.
class HaltonSequence {
 public:
  HaltonSequence(int dims, std::uint64_t seed);
  double at(long index, int dim) const;  ///< point `index`, coordinate `dim`, in [0, 1)

 private:
  std::vector<int> bases_;
  std::vector<double> shifts_;
};

}  // namespace lagrange::tools
