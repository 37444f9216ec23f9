#include "transport/message_size.hpp"

#include "transport/channels.hpp"

namespace lagrange::transport {

namespace {

// LCM's encoding (lcm-gen): a top-level message starts with its 8-byte
// fingerprint; int64 and double take 8 bytes, int32 4, int8 and boolean 1; a
// string its int32 length, its bytes and a NUL.
constexpr long long kFingerprint = 8;
long long stringBytes(long long length) { return 4 + length + 1; }

// header_t: tick, sim_time, publish_utime, run_id, publisher, publisher_pid, seq, checksum.
long long headerBytes() { return 8 + 8 + 8 + 8 + stringBytes(kMaxPublisherBytes) + 4 + 8 + 8; }

std::string plural(long long n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::string MessageShape::describe() const {
  return plural(joints, "joint", "joints") + ", actuator order " + std::to_string(chain_order) + ", " +
         plural(torque_steps, "torque step", "torque steps") + " a tick";
}

namespace encoded_size {

long long plantPosition(const MessageShape& s) { return kFingerprint + headerBytes() + 4 + 8LL * s.joints; }

long long plantTruth(const MessageShape& s) {
  // q, qdot, tau_applied; three energies, input_actuator_tick, torque_source.
  return kFingerprint + headerBytes() + 4 + 3 * 8LL * s.joints + 3 * 8 + 8 + 1;
}

long long plantMotor(const MessageShape& s) {
  // q; num_rates (0, or joints with rate sensors) and qdot.
  return kFingerprint + headerBytes() + 4 + 8LL * s.joints + 4 + 8LL * s.joints;
}

long long controlCommand(const MessageShape& s) {
  // Three input ticks, num_joints, u, q_desired, q_error, theta, filter_state, chain_order, xi_error.
  return kFingerprint + headerBytes() + 3 * 8 + 4 + 5 * 8LL * s.joints + 4 +
         8LL * s.command_stages * s.joints;
}

long long actuatorState(const MessageShape& s) {
  // input_command_tick, num_joints, order, u_commanded, torque_steps, tau_applied, saturated, xi.
  return kFingerprint + headerBytes() + 8 + 4 + 4 + 8LL * s.joints + 4 + 8LL * s.torque_steps * s.joints +
         s.joints + 8LL * s.chain_order * s.joints;
}

}  // namespace encoded_size

long long largestPerTickMessage(const std::string& channel, const MessageShape& shape) {
  if (channel == kPlantPosition || channel == kPlantRate) return encoded_size::plantPosition(shape);
  if (channel == kPlantTruth) return encoded_size::plantTruth(shape);
  if (channel == kPlantMotor) return encoded_size::plantMotor(shape);
  if (channel == kControlCommand) return encoded_size::controlCommand(shape);
  if (channel == kActuatorState) return encoded_size::actuatorState(shape);
  return -1;
}

}  // namespace lagrange::transport
