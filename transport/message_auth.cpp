#include "transport/message_auth.hpp"

#include <sodium.h>

#include <stdexcept>

namespace lagrange::transport {

namespace {
void initSodium() {
  // Idempotent and thread-safe; -1 only when the system has no usable
  // random source, which nothing here can work around.
  if (sodium_init() < 0) throw std::runtime_error("libsodium cannot initialise (no random source?)");
}
}  // namespace

struct MessageAuthenticator::State {
  crypto_auth_hmacsha256_state hmac;
};

MessageKey randomMessageKey() {
  initSodium();
  MessageKey key;
  randombytes_buf(key.data(), key.size());
  return key;
}

std::string toHex(const MessageKey& key) {
  std::string hex(2 * key.size() + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), key.data(), key.size());
  hex.pop_back();
  return hex;
}

bool fromHex(const std::string& text, MessageKey& key) {
  if (text.size() != 2 * key.size()) return false;
  size_t written = 0;
  const char* end = nullptr;
  return sodium_hex2bin(key.data(), key.size(), text.data(), text.size(), nullptr, &written, &end) == 0 &&
         written == key.size() && end == text.data() + text.size();
}

MessageAuthenticator::MessageAuthenticator(const MessageKey& key) : keyed_(new State) {
  initSodium();
  crypto_auth_hmacsha256_init(&keyed_->hmac, key.data(), key.size());
}

MessageAuthenticator::~MessageAuthenticator() {
  sodium_memzero(keyed_, sizeof(State));
  delete keyed_;
}

std::array<uint8_t, kMacBytes> MessageAuthenticator::mac(const uint8_t* data, std::size_t size) const {
  crypto_auth_hmacsha256_state state = keyed_->hmac;
  crypto_auth_hmacsha256_update(&state, data, size);
  std::array<uint8_t, kMacBytes> out;
  crypto_auth_hmacsha256_final(&state, out.data());
  return out;
}

void MessageAuthenticator::sign(std::vector<uint8_t>& datagram) const {
  const std::array<uint8_t, kMacBytes> m = mac(datagram.data(), datagram.size());
  datagram.insert(datagram.end(), m.begin(), m.end());
}

bool MessageAuthenticator::verify(const uint8_t* data, std::size_t size) const {
  if (size < kMacBytes) return false;
  const std::size_t payload = size - kMacBytes;
  const std::array<uint8_t, kMacBytes> expected = mac(data, payload);
  return crypto_verify_32(expected.data(), data + payload) == 0;
}

}  // namespace lagrange::transport
