#pragma once
/// @file
/// A double as text that reads back as the same double ("%.17g"): for CSV
/// files, tables and --set values that must round-trip bit for bit.

#include <cstdio>
#include <string>

namespace lagrange::util {

inline std::string exactText(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace lagrange::util
