#include "lagrange/sdk/external_controller.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <map>

#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/status_t.hpp"
#include "transport/checksum.hpp"

namespace lagrange::sdk {

namespace {

constexpr size_t kMacBytes = 32;
constexpr int64_t kKeepAnswers = 64;  // lockstep re-sends only the tick it awaits

std::string environment(const char* name) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0')
    throw ContractError(std::string(name) +
                        " is not set: an external controller is started by `lagrange run` (controller.type: "
                        "external), which sets LAGRANGE_LCM_URL, LAGRANGE_RUN_ID, LAGRANGE_KEY_FILE, "
                        "LAGRANGE_JOINTS and LAGRANGE_MODE");
  return v;
}

long long integer(const char* name) {
  const std::string text = environment(name);
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0')
    throw ContractError(std::string(name) + "='" + text + "': expected an integer");
  return v;
}

std::array<unsigned char, 32> readKey(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text.size() != 64)
    throw ContractError("the run's key file " + path + " does not hold 64 hex digits");
  std::array<unsigned char, 32> key{};
  for (size_t i = 0; i < 32; ++i) {
    const std::string pair = text.substr(2 * i, 2);
    char* end = nullptr;
    const long b = std::strtol(pair.c_str(), &end, 16);
    if (*end != '\0') throw ContractError("the run's key file " + path + " does not hold 64 hex digits");
    key[i] = static_cast<unsigned char>(b);
  }
  return key;
}

// The checksum is the project's own (transport/checksum.hpp, header-only:
// compiled in here, not installed): lagrange's FNV-1a basis, lowest bit set.
using transport::checksumOf;

int64_t monotonicUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The run's clock (transport/run_clock.hpp): monotonic plus the launcher's offset.
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

class Controller {
 public:
  Controller(const Step& step, const std::function<void()>& reset)
      : step_(step),
        reset_(reset),
        run_id_(integer("LAGRANGE_RUN_ID")),
        joints_(static_cast<int>(integer("LAGRANGE_JOINTS"))),
        key_(readKey(environment("LAGRANGE_KEY_FILE"))),
        lcm_(environment("LAGRANGE_LCM_URL")),
        clock_offset_(clockOffsetUs()) {
    if (!lcm_.good()) throw ContractError("LCM could not be created on " + environment("LAGRANGE_LCM_URL"));
    lcm_.subscribe("PLANT_POSITION", &Controller::onPosition, this);
    lcm_.subscribe("STATUS", &Controller::onStatus, this);
  }

  int serve() {
    auto next_status = std::chrono::steady_clock::now();
    while (!plant_finished_) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= next_status) {  // ten times a second until the first position, then twice
        publishStatus(last_tick_ < 0 ? "ready" : "running");
        next_status = now + std::chrono::milliseconds(last_tick_ < 0 ? 100 : 500);
      }
      const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(
          next_status - std::chrono::steady_clock::now());
      if (lcm_.handleTimeout(static_cast<int>(std::max<int64_t>(1, wait.count()))) < 0)
        throw ContractError("LCM failed while waiting for a message");
      if (!error_.empty()) throw ContractError(error_);
    }
    for (int i = 0; i < 3; ++i) publishStatus("finished");
    return 0;
  }

 private:
  std::array<unsigned char, kMacBytes> mac(const void* data, size_t size) const {
    std::array<unsigned char, kMacBytes> out{};
    size_t written = 0;
    if (EVP_Q_mac(nullptr, "HMAC", nullptr, "SHA256", nullptr, key_.data(), key_.size(),
                  static_cast<const unsigned char*>(data), size, out.data(), out.size(),
                  &written) == nullptr ||
        written != kMacBytes)
      throw ContractError("HMAC-SHA256 failed (libcrypto)");
    return out;
  }

  // The payload of a datagram whose MAC is valid, or false: nothing else is decoded.
  bool authentic(const lcm::ReceiveBuffer* rbuf) const {
    if (rbuf->data_size < kMacBytes) return false;
    const size_t payload = rbuf->data_size - kMacBytes;
    const auto good = mac(rbuf->data, payload);
    return CRYPTO_memcmp(good.data(), static_cast<const unsigned char*>(rbuf->data) + payload, kMacBytes) ==
           0;
  }

  template <class Msg>
  void publish(const std::string& channel, Msg& msg) {
    std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    const auto tag = mac(bytes.data(), bytes.size());
    bytes.insert(bytes.end(), tag.begin(), tag.end());
    if (lcm_.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size())) != 0)
      throw ContractError("LCM could not publish on " + channel);
  }

  void stamp(lagrange::header_t& h, const std::string& channel, int64_t tick, double sim_time) {
    h.tick = std::max<int64_t>(0, tick);
    h.sim_time = sim_time;
    h.publish_utime = monotonicUs() + clock_offset_;
    h.run_id = run_id_;
    h.publisher = "controller";
    h.publisher_pid = static_cast<int32_t>(getpid());
    h.seq = ++seq_[channel];
    h.checksum = 0;
  }

  void publishCommand(lagrange::control_command_t c) {
    stamp(c.header, "CONTROL_COMMAND", c.header.tick, c.header.sim_time);
    c.header.checksum = checksumOf(c);
    publish("CONTROL_COMMAND", c);
  }

  void publishStatus(const std::string& state) {
    lagrange::status_t s{};
    stamp(s.header, "STATUS", last_tick_, 0.0);
    s.process = "controller";
    s.state = state;
    s.last_tick = last_tick_;
    s.tracking_error = std::numeric_limits<double>::quiet_NaN();
    s.num_channels = 0;
    s.header.checksum = checksumOf(s);
    publish("STATUS", s);
  }

  std::vector<double> vector(const std::vector<double>& v, const char* what,
                             const lagrange::plant_position_t& p) const {
    if (v.empty() && std::string(what) != "u") return std::vector<double>(static_cast<size_t>(joints_), 0.0);
    if (static_cast<int>(v.size()) != joints_)
      throw ContractError(std::string("the law returned ") + std::to_string(v.size()) + " numbers for " +
                          what + "; expected " + std::to_string(joints_) + " (one per joint)");
    // The plant would refuse the command and the run stall: say it here, at once.
    for (size_t j = 0; j < v.size(); ++j)
      if (!std::isfinite(v[j]))
        throw ContractError(std::string("the law returned ") + std::to_string(v[j]) + " for " + what + "[" +
                            std::to_string(j) + "] (joint " + std::to_string(j + 1) +
                            ") at the sample of tick " + std::to_string(p.header.tick) +
                            " (t = " + std::to_string(p.header.sim_time) + " s); expected finite numbers");
    return v;
  }

  void onStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    if (!authentic(rbuf)) return;
    lagrange::status_t s;
    if (s.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size - kMacBytes)) < 0) return;
    if (s.header.run_id == run_id_ && s.process == "plant" && s.state == "finished") plant_finished_ = true;
  }

  void onPosition(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    if (!error_.empty() || !authentic(rbuf)) return;
    lagrange::plant_position_t p;
    if (p.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size - kMacBytes)) < 0) return;
    if (p.header.run_id != run_id_ || p.header.publisher != "plant" || p.header.checksum != checksumOf(p) ||
        p.num_joints != joints_ || static_cast<int>(p.q.size()) != joints_)
      return;
    const int64_t tick = p.header.tick;
    if (const auto cached = answered_.find(tick); cached != answered_.end()) {
      publishCommand(cached->second);  // a re-sent position: the same answer, the law not stepped
      return;
    }
    if (tick <= last_tick_) return;  // older than one answered: never step back
    try {
      if (last_tick_ < 0 && reset_) reset_();
      const Command out = step_(p.header.sim_time, p.q);
      lagrange::control_command_t c{};
      c.header.tick = tick;
      c.header.sim_time = p.header.sim_time;
      c.input_position_tick = tick;
      c.input_actuator_tick = -1;
      c.input_motor_tick = -1;
      c.num_joints = joints_;
      c.u = vector(out.u, "u", p);
      c.q_desired = vector(out.q_desired, "q_desired", p);
      c.q_error = vector(out.q_error, "q_error", p);
      c.theta = vector(out.theta, "theta", p);
      c.filter_state = vector(out.filter_state, "filter_state", p);
      c.chain_order = 0;
      answered_[tick] = c;
      answered_.erase(answered_.begin(), answered_.upper_bound(tick - kKeepAnswers));  // skipped ticks too
      last_tick_ = tick;
      publishCommand(c);
    } catch (const std::exception& e) {  // not through LCM's C frames: serve() throws it
      error_ = e.what();
    }
  }

  Step step_;
  std::function<void()> reset_;
  int64_t run_id_;
  int joints_;
  std::array<unsigned char, 32> key_;
  lcm::LCM lcm_;
  int64_t clock_offset_;
  std::map<std::string, int64_t> seq_;
  std::map<int64_t, lagrange::control_command_t> answered_;
  int64_t last_tick_ = -1;
  bool plant_finished_ = false;
  std::string error_;
};

}  // namespace

int run(const Step& step, const std::function<void()>& reset, const std::string& program) {
  try {
    return Controller(step, reset).serve();
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace lagrange::sdk
