#include "logs/event_bounds.hpp"

#include <utility>

#include "config/input_file.hpp"
#include "config/work_bounds.hpp"
#include "transport/channels.hpp"
#include "transport/message_auth.hpp"

namespace lagrange::logs {

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

MessageShape MessageShape::projectLimits() {
  return {config::kMaxJoints, config::kMaxActuatorOrder, static_cast<int>(config::kMaxStepsPerSample)};
}

std::string MessageShape::describe() const {
  return plural(joints, "joint", "joints") + ", actuator order " + std::to_string(chain_order) + ", " +
         plural(torque_steps, "torque step", "torque steps") + " a tick";
}

long long maxScenarioEventBytes() {
  return static_cast<long long>(config::kMaxScenarioBytes + 2 * config::kMaxUrdfBytes) + (64 << 10);
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
  // xi_error has a row per stage of the controller's cascade, which is not
  // the actuator's order (the flexible-joint controller reports 2 stages
  // with actuator.order 0): every controller has at most kMaxActuatorOrder.
  return kFingerprint + headerBytes() + 3 * 8 + 4 + 5 * 8LL * s.joints + 4 +
         8LL * config::kMaxActuatorOrder * s.joints;
}

long long actuatorState(const MessageShape& s) {
  // input_command_tick, num_joints, order, u_commanded, torque_steps, tau_applied, saturated, xi.
  return kFingerprint + headerBytes() + 8 + 4 + 4 + 8LL * s.joints + 4 + 8LL * s.torque_steps * s.joints +
         s.joints + 8LL * s.chain_order * s.joints;
}

}  // namespace encoded_size

EventBounds::EventBounds(const MessageShape& shape, std::string origin)
    : shape_(shape), origin_(std::move(origin)) {
  // A stock lcm-logger records the datagrams with their MAC trailer.
  const auto with_trailer = [](long long bytes) {
    return bytes + static_cast<long long>(transport::kMacBytes);
  };
  largest_ = {
      {transport::kPlantPosition, with_trailer(encoded_size::plantPosition(shape))},
      {transport::kPlantRate, with_trailer(encoded_size::plantPosition(shape))},
      {transport::kPlantTruth, with_trailer(encoded_size::plantTruth(shape))},
      {transport::kPlantMotor, with_trailer(encoded_size::plantMotor(shape))},
      {transport::kControlCommand, with_trailer(encoded_size::controlCommand(shape))},
      {transport::kActuatorState, with_trailer(encoded_size::actuatorState(shape))},
      {transport::kStatus, kMaxStatusEventBytes},
      {transport::kScenario, maxScenarioEventBytes()},
      {transport::kRobotDescription, kMaxDescriptionEventBytes},
  };
}

EventBounds EventBounds::projectLimits(const std::string& why) {
  const MessageShape limits = MessageShape::projectLimits();
  return EventBounds(limits, why + ": the project's limits (" + limits.describe() + ")");
}

long long EventBounds::largestData(const std::string& channel) const {
  const auto it = largest_.find(channel);
  return it == largest_.end() ? -1 : it->second;
}

}  // namespace lagrange::logs
