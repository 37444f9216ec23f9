// transport::SampleHistogram: the realtime loops' percentiles without keeping
// their samples. Against the exact order statistics of the same samples
// (sorting them, transport::percentiles): never below, at most 1 % above,
// never above the maximum, which is exact.
#include "transport/sample_histogram.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "transport/rate_loop.hpp"

namespace lagrange::transport {
namespace {

void expectClose(const SampleHistogram& h, const std::vector<double>& samples) {
  const Percentiles exact = percentiles(samples), binned = h.percentiles();
  EXPECT_EQ(binned.max, exact.max);
  for (const auto& [b, e] : {std::pair{binned.p50, exact.p50}, std::pair{binned.p99, exact.p99}}) {
    EXPECT_GE(b, e);
    EXPECT_LE(b, e * 1.0101 + 1e-300) << "more than one bin above";
    EXPECT_LE(b, exact.max);
  }
}

TEST(SampleHistogram, PercentilesWithinOneBinOfTheExactOnes) {
  std::mt19937_64 rng(7);
  // Wake-up lateness as a loop sees it: mostly tens of microseconds, a tail of milliseconds.
  std::lognormal_distribution<double> lateness(std::log(20e-6), 1.0);
  SampleHistogram h;
  std::vector<double> samples;
  for (int i = 0; i < 100000; ++i) {
    const double x = lateness(rng);
    h.add(x);
    samples.push_back(x);
  }
  EXPECT_EQ(h.count(), 100000);
  expectClose(h, samples);
}

TEST(SampleHistogram, ZerosTinyAndHugeValuesAndTheEmptyCase) {
  SampleHistogram empty;
  EXPECT_EQ(empty.percentiles().max, 0.0);
  EXPECT_EQ(empty.percentiles().p99, 0.0);
  SampleHistogram h;
  std::vector<double> samples;
  for (double x : {0.0, 0.0, 0.0, 5e-10, 3e-9, 250.0}) {  // zeros, below the first edge, past the last
    h.add(x);
    samples.push_back(x);
  }
  const Percentiles p = h.percentiles();
  EXPECT_EQ(p.p50, 0.0) << "three zeros of six: the median is a zero";
  EXPECT_EQ(p.max, 250.0);
  EXPECT_EQ(p.p99, 250.0) << "the overflow bin reports the exact maximum";
  const std::vector<double> two = {1e-3, 1e-3};
  SampleHistogram same;
  for (double x : two) same.add(x);
  EXPECT_EQ(same.percentiles().p50, 1e-3) << "capped at the maximum, never above a sample";
}

}  // namespace
}  // namespace lagrange::transport
