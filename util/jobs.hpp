#pragma once
/// @file
/// How many things a command does at a time: its -j, or one per core.

#include <algorithm>
#include <thread>

namespace lagrange::util {

/// `jobs` when positive, else the machine's cores (at least one).
inline int jobsOrCores(int jobs) {
  return jobs > 0 ? jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace lagrange::util
