#pragma once
/// @file
/// A double as the shortest text that reads back as the same double
/// (std::to_chars: "0.1", not "0.10000000000000001"): for CSV files, tables
/// and --set values that must round-trip bit for bit. Non-finite values as
/// "nan", "inf", "-inf".

#include <charconv>
#include <string>

namespace lagrange::util {

inline std::string exactText(double x) {
  char buf[32];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace lagrange::util
