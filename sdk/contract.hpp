#pragma once
/// @file
/// The wire contract of docs/external_programs.md as the C++ SDK's helpers
/// keep it -- the controller's (external_controller.cpp) and the plant's
/// (external_plant.cpp): the run's environment, its key and the MAC on every
/// datagram, the header every message carries, and a bus that signs and
/// checks them. Private to the SDK's library: not installed, so nothing here
/// is an interface a user's program could come to depend on.

#include <array>
#include <cstddef>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lagrange/header_t.hpp"
#include "lagrange/sdk/external_controller.hpp"
#include "transport/checksum.hpp"

namespace lagrange::sdk::contract {

inline constexpr size_t kMacBytes = 32;

/// The variable's value. @throws ContractError naming it and saying that the
/// program (`role`: "controller", "plant") is started by `lagrange run`.
std::string environment(const char* name, const std::string& role);

/// The variable as an integer. @throws ContractError naming it and its text.
long long integer(const char* name, const std::string& role);

/// CLOCK_MONOTONIC [us].
int64_t monotonicUs();

/// The run's secret key (its key file's 64 hex digits) and HMAC-SHA256 with it.
class Key {
 public:
  /// @throws ContractError naming the file when it does not hold 64 hex digits,
  ///         or when libcrypto offers no HMAC-SHA256.
  explicit Key(const std::string& path);
  /// @throws ContractError when libcrypto fails.
  std::array<unsigned char, kMacBytes> mac(const void* data, size_t size) const;
  /// Whether a datagram ends in the MAC of what precedes it (constant time).
  /// False also when libcrypto fails: what cannot be checked is not trusted.
  bool authentic(const void* data, size_t size) const noexcept;

 private:
  std::array<unsigned char, 32> key_{};
  // One HMAC context keyed once and re-initialised for each message (as
  // transport/message_auth.cpp): EVP_Q_mac fetched the algorithm and built a
  // context every call, tens of microseconds a message -- most of a plant's
  // period in the C++ helper. Shared by copies; the lock keeps mac() const-safe.
  struct Context;
  std::shared_ptr<Context> context_;
};

/// The headers one process stamps: its run, its name, its pid, one sequence
/// number per channel (re-sent messages included) and the run's clock.
class Headers {
 public:
  Headers(int64_t run_id, std::string publisher);
  /// The run's clock now [us]: CLOCK_MONOTONIC plus the launcher's offset.
  int64_t utime() const;
  /// Fills `h` for the next message on `channel`, checksum 0 (seal it last).
  void stamp(lagrange::header_t& h, const std::string& channel, int64_t tick, double sim_time);

 private:
  int64_t run_id_;
  std::string publisher_;
  int32_t pid_;
  int64_t clock_offset_us_;
  std::map<std::string, int64_t> seq_;
};

/// Why a datagram was dropped, or kAccepted.
enum class Verdict { kAccepted, kUnauthenticated, kUndecodable, kOtherRun, kCorrupt };

/// "MAC", "undecodable", "another run", "checksum": the words a stall's
/// diagnosis counts them under.
const char* reasonOf(Verdict v);

/// The run's bus as one process sees it: LCM on LAGRANGE_LCM_URL, the key
/// of LAGRANGE_KEY_FILE, LAGRANGE_RUN_ID, and this process's headers.
class Bus {
 public:
  /// `role`: the publisher name and the process the run started ("controller", "plant").
  explicit Bus(const std::string& role);

  lcm::LCM& lcm() { return lcm_; }
  int64_t runId() const { return run_id_; }
  /// The run's clock now [us], as this process stamps publish_utime.
  int64_t utime() const { return headers_.utime(); }

  /// Stamps `msg`'s header (a new seq: re-sent copies too), seals it, signs
  /// the encoding and publishes it. @throws ContractError when LCM cannot.
  template <class Msg>
  void publish(const std::string& channel, Msg& msg, int64_t tick, double sim_time) {
    headers_.stamp(msg.header, channel, tick, sim_time);
    transport::seal(msg);
    std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    send(channel, std::move(bytes));
  }

  /// Decodes `out` from a datagram of this run with a valid MAC and an
  /// intact checksum; the MAC is checked before anything is decoded.
  template <class Msg>
  Verdict receive(const lcm::ReceiveBuffer* rbuf, Msg& out) const {
    if (!key_.authentic(rbuf->data, rbuf->data_size)) return Verdict::kUnauthenticated;
    if (out.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size - kMacBytes)) < 0)
      return Verdict::kUndecodable;
    if (out.header.run_id != run_id_) return Verdict::kOtherRun;
    if (!transport::intact(out)) return Verdict::kCorrupt;
    return Verdict::kAccepted;
  }

  /// Handles what arrives within `timeout_ms` (0: what is there); the number
  /// of datagrams handled, 0 also when a signal cut the wait short.
  /// @throws ContractError when LCM fails.
  int handle(int timeout_ms);

 private:
  void send(const std::string& channel, std::vector<uint8_t> bytes);

  std::string url_;
  int64_t run_id_;
  Key key_;
  Headers headers_;
  lcm::LCM lcm_;
};

}  // namespace lagrange::sdk::contract
