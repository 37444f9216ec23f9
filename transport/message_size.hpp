#pragma once
/// @file
/// How large an honest per-tick message can be. A run's scenario fixes the
/// counts in every per-tick message (the arm's joints, the actuator's order,
/// the torque steps a tick); with them each message type has a largest
/// encoded size. A message larger than that is not one of the run's, and
/// need not be decoded to know it: the message decoders (safe_decode.hpp) may
/// allocate 64 bytes per byte received, and lcm-gen's types cost far more
/// memory than their bytes for many short rows (one ACTUATOR_STATE of 30
/// million one-joint rows, 241 MB, took a reader to 3.5 GB). The log readers
/// skip such events unread (logs/event_bounds.hpp); a live process could
/// reject such datagrams the same way.
///
/// The sizes follow lcm-gen's encoding of lcmtypes/*.lcm; a unit test holds
/// them to getEncodedSize() of messages with the same counts.

#include <string>

namespace lagrange::transport {

/// The counts that size a run's per-tick messages.
struct MessageShape {
  int joints = 0;          ///< num_joints of every per-tick message (and num_rates of PLANT_MOTOR at most)
  int chain_order = 0;     ///< actuator.order: rows of ACTUATOR_STATE.xi
  int torque_steps = 1;    ///< actuator.rate / plant.publish_rate: rows of ACTUATOR_STATE.tau_applied
  int command_stages = 0;  ///< rows of CONTROL_COMMAND.xi_error: the controller's cascade, which is not
                           ///< the actuator's order (the flexible-joint controller reports 2 with order 0)

  /// "2 joints, actuator order 0, 1 torque step a tick"
  std::string describe() const;
};

/// Longest publisher name a message's header may carry: the project's are
/// "plant", "controller", "actuator", "logger"; an external controller's
/// messages carry "controller" too.
inline constexpr long long kMaxPublisherBytes = 64;

/// The encoded size of the largest honest message of each per-tick type with
/// `shape`'s counts and a publisher of kMaxPublisherBytes, without the MAC
/// trailer (message_auth.hpp).
namespace encoded_size {
long long plantPosition(const MessageShape& shape);  ///< also PLANT_RATE (the same layout)
long long plantTruth(const MessageShape& shape);
long long plantMotor(const MessageShape& shape);
long long controlCommand(const MessageShape& shape);
long long actuatorState(const MessageShape& shape);
}  // namespace encoded_size

/// The largest honest message on a per-tick channel (channels.hpp) with
/// `shape`'s counts, without the MAC trailer; -1 for any other channel.
long long largestPerTickMessage(const std::string& channel, const MessageShape& shape);

}  // namespace lagrange::transport
