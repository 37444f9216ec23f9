#pragma once
/// @file
/// Authenticated messages (DESIGN section 6, docs/reliability.md "Threat
/// model"). Anyone on a run's multicast group can read its run id off the
/// wire and publish with it, so the run id proves nothing. Each run has a
/// secret key instead; every datagram is the message's LCM encoding followed
/// by a 32-byte trailer, HMAC-SHA256 of that encoding under the key
/// (OpenSSL's libcrypto computes it; libsodium draws the key and compares). A receiver checks the trailer, in
/// constant time, before any byte of the payload reaches a decoder, and drops what fails.
///
/// Why a trailer and not a field of header_t: the message types stay as they
/// were, so lcm-spy and any LCM decoder (which read a message's fields and
/// ignore what follows) still decode every channel, SCENARIO and
/// ROBOT_DESCRIPTION are covered like the rest, and the logger records the
/// verified encodings without the trailer -- a log reads as before.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lagrange::transport {

/// A run's secret: 32 bytes from a cryptographic random source.
using MessageKey = std::array<uint8_t, 32>;

/// Bytes of the trailer every authenticated datagram ends with.
inline constexpr std::size_t kMacBytes = 32;

/// A fresh key from the operating system's cryptographic random source
/// (libsodium's randombytes_buf: getrandom(2)).
MessageKey randomMessageKey();

/// 32 fresh bytes from the same source: a run's own value (below).
std::array<uint8_t, 32> randomNonce();

/// The key a run's processes sign with when several runs share a key (a key
/// file reused across runs, the hosts of a run spread with --processes):
/// HMAC-SHA256 under the shared key of a label and a value fresh for this
/// run. Traffic recorded from another run under the same shared key carries
/// MACs under another run key, and fails. Without the shared key nobody
/// can compute it; with the run key alone nobody can recover the shared one.
MessageKey deriveRunKey(const MessageKey& shared, const std::array<uint8_t, 32>& run_value);

/// SHA-256 of `size` bytes (OpenSSL's libcrypto).
std::array<uint8_t, 32> sha256(const uint8_t* data, std::size_t size);

/// The key as 64 lowercase hex digits (the key file's format).
std::string toHex(const MessageKey& key);
/// 64 hex digits (either case) as a key; false if `text` is anything else.
bool fromHex(const std::string& text, MessageKey& key);

/// Signs and checks datagrams with one key. The keyed HMAC state is computed
/// once; each message costs the hash of its bytes only.
class MessageAuthenticator {
 public:
  explicit MessageAuthenticator(const MessageKey& key);
  ~MessageAuthenticator();
  MessageAuthenticator(const MessageAuthenticator&) = delete;
  MessageAuthenticator& operator=(const MessageAuthenticator&) = delete;

  /// Appends the trailer: HMAC-SHA256 of the bytes now in `datagram`.
  void sign(std::vector<uint8_t>& datagram) const;
  /// The MAC of `size` bytes.
  std::array<uint8_t, kMacBytes> mac(const uint8_t* data, std::size_t size) const;
  /// True when `size` bytes are a payload followed by its valid trailer
  /// (compared in constant time). Never reads past `size`.
  bool verify(const uint8_t* data, std::size_t size) const;

 private:
  struct State;
  State* keyed_;  ///< the HMAC state after the key, copied for each message
};

}  // namespace lagrange::transport
