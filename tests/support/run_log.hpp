#pragma once
/// @file
/// Reading a run's outputs in tests: PLANT_TRUTH samples from run.lcm
/// (through LCM's own log API) and summary.json.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "logs/log_reader.hpp"
#include "transport/checksum.hpp"
#include "transport/messages.hpp"
#include "transport/safe_decode.hpp"

namespace lagrange::testing {

struct TruthSample {
  long long tick;
  double t;
  Eigen::VectorXd q, qdot;
  double energy;
  int torque_source;    ///< plant_truth_t::TORQUE_COMMANDED, TORQUE_HELD or TORQUE_ZERO
  Eigen::VectorXd tau;  ///< the torque applied over the period that ended here (its first step)
};

/// One sample per tick (retransmissions dropped), in tick order.
inline std::vector<TruthSample> readTruth(const std::string& log_path) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) throw std::runtime_error("cannot open " + log_path);
  std::map<long long, TruthSample> by_tick;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    if (ev->channel != "PLANT_TRUTH") continue;
    lagrange::plant_truth_t m;
    // A copy corrupted on the way (recorded as it arrived) is skipped; the intact one is re-sent.
    if (!transport::safeDecode(ev->data, static_cast<size_t>(ev->datalen), m) ||
        (m.header.checksum != 0 && !transport::intact(m)))
      continue;
    by_tick.emplace(m.header.tick, TruthSample{m.header.tick, m.header.sim_time, transport::toEigen(m.q),
                                               transport::toEigen(m.qdot), m.total_energy, m.torque_source,
                                               transport::toEigen(m.tau_applied)});
  }
  std::vector<TruthSample> out;
  for (auto& [tick, s] : by_tick) out.push_back(s);
  return out;
}

/// Samples present in both a and b, matched by tick (a comparison that a
/// sample lost by a logger does not misalign; completeness is tested apart).
template <class F>
inline size_t forCommonTicks(const std::vector<TruthSample>& a, const std::vector<TruthSample>& b, F each) {
  std::map<long long, const TruthSample*> in_b;
  for (const auto& s : b) in_b[s.tick] = &s;
  size_t common = 0;
  for (const auto& s : a)
    if (const auto it = in_b.find(s.tick); it != in_b.end()) {
      each(s, *it->second);
      ++common;
    }
  return common;
}

/// (channel, header.tick) of every PLANT_POSITION, PLANT_TRUTH,
/// CONTROL_COMMAND and ACTUATOR_STATE event, in log order.
inline std::vector<std::pair<std::string, long long>> readTicks(const std::string& log_path) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) throw std::runtime_error("cannot open " + log_path);
  std::vector<std::pair<std::string, long long>> out;
  // As lagrange's readers decode: corrupted copies skipped, and a run's MAC
  // trailer skipped where another logger (a stock lcm-logger) recorded it.
  auto note = [&](const lcm::LogEvent& ev, auto message) {
    if (logs::decodeEvent(ev, message)) out.emplace_back(ev.channel, message.header.tick);
  };
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    if (ev->channel == "PLANT_POSITION") note(*ev, lagrange::plant_position_t{});
    if (ev->channel == "PLANT_TRUTH") note(*ev, lagrange::plant_truth_t{});
    if (ev->channel == "CONTROL_COMMAND") note(*ev, lagrange::control_command_t{});
    if (ev->channel == "ACTUATOR_STATE") note(*ev, lagrange::actuator_state_t{});
  }
  return out;
}

/// The largest |rate| a channel's samples carry: PLANT_TRUTH (joint rates q')
/// or PLANT_MOTOR (measured motor rates q2'), intact copies only.
inline double peakRate(const std::string& log_path, const std::string& channel) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) throw std::runtime_error("cannot open " + log_path);
  double peak = 0.0;
  auto take = [&](const lcm::LogEvent& ev, auto message) {
    if (!transport::safeDecode(ev.data, static_cast<size_t>(ev.datalen), message) ||
        (message.header.checksum != 0 && !transport::intact(message)))
      return;
    for (const double rate : message.qdot) peak = std::max(peak, std::abs(rate));
  };
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    if (ev->channel != channel) continue;
    if (channel == "PLANT_TRUTH") take(*ev, lagrange::plant_truth_t{});
    if (channel == "PLANT_MOTOR") take(*ev, lagrange::plant_motor_t{});
  }
  return peak;
}

/// Every event's channel, in log order.
inline std::vector<std::string> readChannels(const std::string& log_path) {
  lcm::LogFile log(log_path, "r");
  std::vector<std::string> out;
  while (const lcm::LogEvent* ev = log.readNextEvent()) out.push_back(ev->channel);
  return out;
}

/// The first copy of each tick's vector `field` on a per-tick channel:
/// PLANT_POSITION q (what the sensor read), PLANT_RATE qdot, CONTROL_COMMAND u.
template <class Msg>
std::map<long long, std::vector<double>> readReadings(const std::string& log_path, const std::string& channel,
                                                      std::vector<double> Msg::*field) {
  lcm::LogFile log(log_path, "r");
  std::map<long long, std::vector<double>> by_tick;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    if (ev->channel != channel) continue;
    Msg m;
    if (m.decode(ev->data, 0, ev->datalen) < 0) throw std::runtime_error("bad " + channel);
    by_tick.emplace(m.header.tick, m.*field);
  }
  return by_tick;
}

inline std::map<long long, std::vector<double>> readPositions(const std::string& log_path) {
  return readReadings(log_path, "PLANT_POSITION", &lagrange::plant_position_t::q);
}

inline std::map<long long, std::vector<double>> readRates(const std::string& log_path) {
  return readReadings(log_path, "PLANT_RATE", &lagrange::plant_rate_t::qdot);
}

inline std::map<long long, std::vector<double>> readCommands(const std::string& log_path) {
  return readReadings(log_path, "CONTROL_COMMAND", &lagrange::control_command_t::u);
}

inline nlohmann::json readSummary(const std::string& dir) {
  std::ifstream in(dir + "/summary.json");
  if (!in) throw std::runtime_error("no summary.json in " + dir);
  return nlohmann::json::parse(in);
}

}  // namespace lagrange::testing
