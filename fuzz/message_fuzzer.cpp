/// @file
/// libFuzzer target: arbitrary bytes into every message decoder of the
/// project, and every decoded message into its validator -- what a process
/// does with each datagram before anything reaches the mathematics
/// (transport/lcm_node.hpp, transport/messages.cpp). The first byte picks the
/// type, the rest is the datagram. A crash, a sanitizer report (ASan, UBSan)
/// or an exception escaping is a finding.
///
/// Run: bash scripts/fuzz.sh [SECONDS]   (corpus: fuzz/corpus/messages)

#include <cstddef>
#include <cstdint>
#include <string>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/channel_stats_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "lagrange/robot_description_t.hpp"
#include "lagrange/scenario_t.hpp"
#include "lagrange/status_t.hpp"
#include "tools/view/view_frames.hpp"
#include "transport/messages.hpp"
#include "transport/safe_decode.hpp"

namespace {

// Decodes as LcmNode::subscribe and the log reader do, then validates.
template <class Msg, class Validate>
void decodeAndValidate(const uint8_t* data, size_t size, Validate validate) {
  Msg m;
  if (!lagrange::transport::safeDecode(data, size, m)) return;
  const std::string why = validate(m);
  (void)why;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t selector = data[0];
  ++data;
  --size;
  using namespace lagrange;
  // The joint count and torque steps a process would expect: 1..4 joints, 1..3 steps.
  const int joints = 1 + (selector >> 4) % 4;
  const int steps = 1 + (selector >> 6) % 3;
  switch (selector % 9) {
    case 0:
      decodeAndValidate<plant_position_t>(data, size,
                                          [&](const auto& m) { return transport::validate(m, joints); });
      break;
    case 1:
      decodeAndValidate<plant_truth_t>(data, size,
                                       [&](const auto& m) { return transport::validate(m, joints); });
      break;
    case 2:
      decodeAndValidate<plant_motor_t>(
          data, size, [&](const auto& m) { return transport::validate(m, joints, selector & 8); });
      break;
    case 3:
      decodeAndValidate<control_command_t>(data, size,
                                           [&](const auto& m) { return transport::validate(m, joints); });
      break;
    case 4:
      decodeAndValidate<actuator_state_t>(
          data, size, [&](const auto& m) { return transport::validate(m, joints, steps); });
      break;
    case 5:
      decodeAndValidate<status_t>(data, size, [&](const auto& m) { return transport::validate(m); });
      break;
    case 6:
      decodeAndValidate<scenario_t>(data, size, [](const auto& m) { return m.yaml.empty() ? "empty" : ""; });
      break;
    case 7:
      decodeAndValidate<robot_description_t>(data, size,
                                             [](const auto& m) { return tools::descriptionProblem(m); });
      break;
    default:
      decodeAndValidate<channel_stats_t>(data, size, [](const auto&) { return std::string(); });
      break;
  }
  return 0;
}
