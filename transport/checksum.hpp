#pragma once
/// @file
/// An end-to-end checksum in every message (header_t.checksum): LCM has
/// none, and a byte flipped inside a number decodes to a plausible wrong
/// value that no validator can catch. The checksum is FNV-1a (64 bit) of the
/// message encoded with checksum = 0; LcmNode::publish seals every message,
/// every subscription checks it.

#include <cstdint>
#include <vector>

namespace lagrange::transport {

/// FNV-1a, 64 bit, with the offset basis 1469598103934665603 -- not the
/// standard 14695981039346656037: a digit was lost when this was first
/// written. Every recorded log carries checksums made this way, so it stays;
/// a program that publishes to a run must use the same basis
/// (docs/external_programs.md).
inline uint64_t fnv1a(const uint8_t* data, size_t size) {
  uint64_t h = 1469598103934665603ULL;
  for (size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ULL;
  return h;
}

/// The checksum of `msg` as if its header.checksum were 0.
template <class Msg>
int64_t checksumOf(Msg msg) {
  msg.header.checksum = 0;
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  // Never 0: 0 means "not sealed".
  return static_cast<int64_t>(fnv1a(bytes.data(), bytes.size()) | 1ULL);
}

/// Sets header.checksum; every other field must be final.
template <class Msg>
void seal(Msg& msg) {
  msg.header.checksum = checksumOf(msg);
}

/// True when header.checksum matches the rest of the message.
template <class Msg>
bool intact(const Msg& msg) {
  return msg.header.checksum == checksumOf(msg);
}

}  // namespace lagrange::transport
