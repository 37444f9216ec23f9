#pragma once
/// @file
/// The clock every header's publish_utime is stamped with: the monotonic
/// clock (CLOCK_MONOTONIC) moved onto the wall clock by one offset, in µs.
/// Monotonic, so a stamp never goes backwards when the wall clock is stepped;
/// one offset for every process of a run on a host (the launcher measures
/// it once and hands it down in LAGRANGE_CLOCK_OFFSET_US), so a latency
/// between two of them -- a position's stamp to the command answering it --
/// is the time that passed and never negative. A process started without it
/// (another host of a run spread with --processes, a program run by hand)
/// measures its own.

#include <cstdint>

namespace lagrange::transport {

inline constexpr const char* kClockOffsetVariable = "LAGRANGE_CLOCK_OFFSET_US";

/// Wall minus monotonic [µs]: LAGRANGE_CLOCK_OFFSET_US when it holds an
/// integer, else measured once (the first call) in this process.
int64_t clockOffsetUs();

/// CLOCK_MONOTONIC [µs].
int64_t monotonicUs();

}  // namespace lagrange::transport
