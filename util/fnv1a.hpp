#pragma once
/// @file
/// FNV-1a, 64 bit, with the standard offset basis: a fingerprint of text
/// (which scenario a file was made for), not a defence against anyone.
/// Message checksums use transport/checksum.hpp's own basis, which recorded
/// logs fix.

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace lagrange::util {

inline std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
  return h;
}

/// fnv1a64 as 16 lower-case hex digits.
inline std::string fnv1a64Hex(std::string_view bytes) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64(bytes)));
  return hex;
}

}  // namespace lagrange::util
