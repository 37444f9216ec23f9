#include "sdk/contract.hpp"

#include <openssl/core_names.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/params.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <utility>

namespace lagrange::sdk::contract {

std::string environment(const char* name, const std::string& role) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0')
    throw ContractError(std::string(name) + " is not set: an external " + role +
                        " is started by `lagrange run` (" + role +
                        ".type: external), which sets LAGRANGE_LCM_URL, LAGRANGE_RUN_ID, LAGRANGE_KEY_FILE, "
                        "LAGRANGE_JOINTS and LAGRANGE_MODE");
  return v;
}

long long integer(const char* name, const std::string& role) {
  const std::string text = environment(name, role);
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0')
    throw ContractError(std::string(name) + "='" + text + "': expected an integer");
  return v;
}

int64_t monotonicUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

namespace {

// The run's clock (transport/run_clock.hpp): monotonic plus the launcher's
// offset, the same for every process of the run; our own when not given.
int64_t clockOffsetUs() {
  if (const char* text = std::getenv("LAGRANGE_CLOCK_OFFSET_US")) {
    char* end = nullptr;
    const long long v = std::strtoll(text, &end, 10);
    if (end != text && *end == '\0') return v;
  }
  const int64_t wall = std::chrono::duration_cast<std::chrono::microseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count();
  return wall - monotonicUs();
}

}  // namespace

struct Key::Context {
  explicit Context(const std::array<unsigned char, 32>& key) {
    char digest[] = "SHA256";
    const OSSL_PARAM params[] = {OSSL_PARAM_construct_utf8_string(OSSL_MAC_PARAM_DIGEST, digest, 0),
                                 OSSL_PARAM_construct_end()};
    mac = EVP_MAC_fetch(nullptr, "HMAC", nullptr);
    keyed = mac ? EVP_MAC_CTX_new(mac) : nullptr;
    if (!keyed || EVP_MAC_init(keyed, key.data(), key.size(), params) != 1) {
      EVP_MAC_CTX_free(keyed);
      EVP_MAC_free(mac);
      throw ContractError(
          "libcrypto offers no HMAC-SHA256 here (EVP_MAC_fetch or EVP_MAC_init failed); "
          "expected OpenSSL 3's default provider");
    }
  }
  ~Context() {
    EVP_MAC_CTX_free(keyed);  // clears the key it holds
    EVP_MAC_free(mac);
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  EVP_MAC* mac = nullptr;
  EVP_MAC_CTX* keyed = nullptr;  ///< keyed once; EVP_MAC_init without a key re-uses it
  std::mutex lock;
};

Key::Key(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text.size() != 64)
    throw ContractError("the run's key file " + path + " does not hold 64 hex digits");
  for (size_t i = 0; i < key_.size(); ++i) {
    const std::string pair = text.substr(2 * i, 2);
    char* end = nullptr;
    const long b = std::strtol(pair.c_str(), &end, 16);
    if (*end != '\0') throw ContractError("the run's key file " + path + " does not hold 64 hex digits");
    key_[i] = static_cast<unsigned char>(b);
  }
  context_ = std::make_shared<Context>(key_);
}

std::array<unsigned char, kMacBytes> Key::mac(const void* data, size_t size) const {
  std::array<unsigned char, kMacBytes> out{};
  size_t written = 0;
  const std::lock_guard<std::mutex> hold(context_->lock);
  if (EVP_MAC_init(context_->keyed, nullptr, 0, nullptr) != 1 ||
      EVP_MAC_update(context_->keyed, static_cast<const unsigned char*>(data), size) != 1 ||
      EVP_MAC_final(context_->keyed, out.data(), &written, out.size()) != 1 || written != kMacBytes)
    throw ContractError("HMAC-SHA256 failed (libcrypto)");
  return out;
}

bool Key::authentic(const void* data, size_t size) const noexcept {
  if (size < kMacBytes) return false;
  const size_t payload = size - kMacBytes;
  try {
    const auto good = mac(data, payload);
    return CRYPTO_memcmp(good.data(), static_cast<const unsigned char*>(data) + payload, kMacBytes) == 0;
  } catch (const ContractError&) {
    return false;
  }
}

Headers::Headers(int64_t run_id, std::string publisher)
    : run_id_(run_id),
      publisher_(std::move(publisher)),
      pid_(static_cast<int32_t>(getpid())),
      clock_offset_us_(clockOffsetUs()) {}

int64_t Headers::utime() const { return monotonicUs() + clock_offset_us_; }

void Headers::stamp(lagrange::header_t& h, const std::string& channel, int64_t tick, double sim_time) {
  h.tick = std::max<int64_t>(0, tick);
  h.sim_time = sim_time;
  h.publish_utime = utime();
  h.run_id = run_id_;
  h.publisher = publisher_;
  h.publisher_pid = pid_;
  h.seq = ++seq_[channel];
  h.checksum = 0;
}

const char* reasonOf(Verdict v) {
  switch (v) {
    case Verdict::kUnauthenticated:
      return "MAC";
    case Verdict::kUndecodable:
      return "undecodable";
    case Verdict::kOtherRun:
      return "another run";
    case Verdict::kCorrupt:
      return "checksum";
    case Verdict::kAccepted:
      break;
  }
  return "accepted";
}

Bus::Bus(const std::string& role)
    : url_(environment("LAGRANGE_LCM_URL", role)),
      run_id_(integer("LAGRANGE_RUN_ID", role)),
      key_(environment("LAGRANGE_KEY_FILE", role)),
      headers_(run_id_, role),
      lcm_(url_) {
  if (!lcm_.good()) throw ContractError("LCM could not be created on " + url_ + " (LAGRANGE_LCM_URL)");
}

int Bus::handle(int timeout_ms) {
  const int handled = lcm_.handleTimeout(std::max(0, timeout_ms));
  if (handled >= 0) return handled;
  if (errno == EINTR) return 0;  // a signal (a stop, a SIGCONT): the caller looks at its flags
  throw ContractError("LCM failed while waiting for a message on " + url_);
}

void Bus::send(const std::string& channel, std::vector<uint8_t> bytes) {
  const auto tag = key_.mac(bytes.data(), bytes.size());
  bytes.insert(bytes.end(), tag.begin(), tag.end());
  if (lcm_.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size())) != 0)
    throw ContractError("LCM could not publish on " + channel + " (" + url_ + ")");
}

}  // namespace lagrange::sdk::contract
