#include "config/key_ranges.hpp"

#include <cstdio>
#include <regex>

namespace lagrange::config {

std::string shortNumber(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent = exponent.substr(1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::string rangeText(const KeyRange& r) {
  const std::string unit = r.unit.empty() ? "" : " " + r.unit;
  if (r.min_exclusive) return "> " + shortNumber(r.min) + " and at most " + shortNumber(r.max) + unit;
  return "from " + shortNumber(r.min) + " to " + shortNumber(r.max) + unit;
}

std::string rangeKey(const std::string& key_path) {
  static const std::regex index(R"(\[[0-9]+\])");
  static const std::regex channel(R"(^faults\.channels\.[^.]+\.)");
  static const std::regex receiver(R"(^faults\.receivers\.[^.]+\.)");
  std::string key = std::regex_replace(key_path, index, "[i]");
  key = std::regex_replace(key, channel, "faults.channels.NAME.");
  key = std::regex_replace(key, receiver, "faults.receivers.PROCESS.");
  if (key == "actuator.initial_state[i].row") key = "actuator.initial_state";
  return key;
}

namespace {
// Shared ranges. Angles may be multi-turn; rates and gains stay far below
// where their products (gain x error x rate) leave double's range.
const KeyRange kAngle{-1e6, 1e6, false, "rad", ""};
const KeyRange kRate{-1e4, 1e4, false, "rad/s", "about 95 000 rpm"};
const KeyRange kGain{0.0, 1e12, true, "",
                     "gains beyond 1e12 overflow or swamp the physics; the paper's constructive "
                     "gains for long chains (check-gains --suggest) reach 1e125 and are evaluated "
                     "there, not run"};
const KeyRange kProbability{0.0, 1.0, false, "", ""};
const KeyRange kFaultDelay{0.0, 60.0, false, "s", "a datagram held longer is lost, not late"};
const KeyRange kNoise{0.0, 1e3, false, "", ""};
const KeyRange kCounts{0.0, 1e12, false, "", ""};
const KeyRange kSensorDelay{0.0, 1e5, false, "samples", "each sensor keeps that many readings"};
const KeyRange kSeed{0.0, 1e9, false, "", ""};
}  // namespace

const std::map<std::string, KeyRange>& keyRanges() {
  static const std::map<std::string, KeyRange> table = {
      {"duration",
       {0.0, 1e9, true, "s", "the samples, physics steps, memory and log it asks for are bounded too"}},
      {"robot.links[i].length", {1e-4, 1e3, false, "m", ""}},
      {"robot.links[i].com", {0.0, 1e3, false, "m", ""}},
      {"robot.links[i].mass", {1e-6, 1e6, false, "kg", ""}},
      {"robot.links[i].inertia", {1e-12, 1e6, false, "kg m^2", ""}},
      {"robot.gravity", {0.0, 1e3, false, "m/s^2", "about 100 g"}},
      {"robot.flexible.stiffness", {0.0, 1e12, true, "N m/rad", ""}},
      {"robot.flexible.rotor_inertia", {1e-12, 1e6, false, "kg m^2", ""}},
      {"initial_state.q", kAngle},
      {"initial_state.qdot", kRate},
      {"initial_state.motor_q", kAngle},
      {"initial_state.motor_qdot", kRate},
      {"reference.initial_q", kAngle},
      {"reference.initial_qdot", kRate},
      {"reference.offset", kAngle},
      {"reference.amplitude", kAngle},
      {"reference.frequency",
       {0.0, 1e4, false, "rad/s", "1.6 kHz, above the Nyquist frequency of any arm's controller"}},
      {"reference.phase", kAngle},
      {"reference.alpha", {1e-6, 1e6, false, "1/s^3", "a start-up between 0.03 s and 300 s"}},
      {"plant.physics_step",
       {1e-7, 1.0, false, "s",
        "a step below 0.1 us only adds rounding; the steps a run asks for are bounded too"}},
      {"plant.publish_rate", {0.1, 1e5, false, "Hz", ""}},
      {"plant.max_rate", {0.0, 1e9, true, "rad/s", ""}},
      {"actuator.order", {0.0, 4.0, false, "", ""}},
      {"actuator.rate", {0.1, 1e6, false, "Hz", ""}},
      {"actuator.saturation", {0.0, 1e12, true, "N m", ""}},
      {"actuator.initial_state", {-1e15, 1e15, false, "", ""}},
      {"controller.kp", kGain},
      {"controller.kd", kGain},
      {"controller.a", kGain},
      {"controller.b", kGain},
      {"controller.lp", kGain},
      {"controller.ld", kGain},
      {"controller.lambda", kGain},
      {"controller.motor_rate_pole", kGain},
      {"controller.initial_filter_state", {-1e15, 1e15, false, "", ""}},
      {"controller.stages[i].kp", kGain},
      {"controller.stages[i].kd", kGain},
      {"controller.stages[i].a", kGain},
      {"controller.stages[i].b", kGain},
      {"controller.stages[i].initial_filter_state", {-1e15, 1e15, false, "", ""}},
      {"controller.stages[i].initial_zeta", {-1e15, 1e15, false, "", ""}},
      {"metrics.tolerance", {0.0, 1e6, true, "rad", ""}},
      {"metrics.convergence_deadline", {0.0, 1e9, true, "s", ""}},
      {"metrics.xi_tolerance", {0.0, 1e15, true, "", ""}},
      {"lockstep.retransmit_timeout",
       {1e-3, 3600.0, false, "s",
        "faster re-sends flood the bus and the log, where each is recorded, before an answer can come back"}},
      {"lockstep.logger_window", {1.0, 1e4, false, "ticks", ""}},
      {"lockstep.stall_timeout",
       {0.1, 86400.0, false, "s",
        "shorter would stop runs that are only slow (a loaded machine, a sanitizer build); a day is past any "
        "run's pause"}},
      {"realtime.max_torque_age", {1.0, 1e6, false, "periods", ""}},
      {"realtime.hold_periods", {0.0, 1e6, false, "periods", ""}},
      {"realtime.max_input_age", {1e-6, 3600.0, false, "s", ""}},
      {"realtime.priority", {0.0, 99.0, false, "", ""}},
      {"supervision.max_restarts", {0.0, 1000.0, false, "", ""}},
      {"faults.seed", kSeed},
      {"faults.channels.NAME.drop", kProbability},
      {"faults.channels.NAME.duplicate", kProbability},
      {"faults.channels.NAME.reorder", kProbability},
      {"faults.channels.NAME.corrupt", kProbability},
      {"faults.channels.NAME.delay", kFaultDelay},
      {"faults.channels.NAME.delay_jitter", kFaultDelay},
      {"faults.receivers.PROCESS.drop", kProbability},
      {"sensors.seed", kSeed},
      {"sensors.position.counts_per_revolution", kCounts},
      {"sensors.position.noise_sigma", kNoise},
      {"sensors.position.delay", kSensorDelay},
      {"sensors.velocity.noise_sigma", kNoise},
      {"sensors.velocity.delay", kSensorDelay},
      {"sensors.motor.counts_per_revolution", kCounts},
      {"sensors.motor.noise_sigma", kNoise},
      {"sensors.motor.delay", kSensorDelay},
  };
  return table;
}

const KeyRange* rangeOf(const std::string& key_path) {
  const auto& table = keyRanges();
  const auto it = table.find(rangeKey(key_path));
  return it == table.end() ? nullptr : &it->second;
}

}  // namespace lagrange::config
