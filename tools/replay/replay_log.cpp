#include "tools/replay/replay_log.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <set>

#include "logs/log_reader.hpp"
#include "transport/channels.hpp"
#include "util/number_text.hpp"

namespace lagrange::tools::replay_log {

namespace {

// Keeps the first copy of each tick (lockstep re-sends are identical).
struct FirstCopies {
  std::set<int64_t> commands, states, truths;
};

// Where each message type goes: every position, rate and motor sample by tick; the
// first copy of each truth, actuator state and command in order too.
void keep(const lagrange::plant_position_t& m, Recorded& r, FirstCopies&) {
  r.positions.emplace(m.header.tick, m);
}
void keep(const lagrange::plant_truth_t& m, Recorded& r, FirstCopies& seen) {
  if (seen.truths.insert(m.header.tick).second) r.truths.push_back(m);
}
void keep(const lagrange::actuator_state_t& m, Recorded& r, FirstCopies& seen) {
  if (seen.states.insert(m.header.tick).second) {
    r.actuator.emplace(m.header.tick, m);
    r.states.push_back(m);
  }
}
void keep(const lagrange::plant_motor_t& m, Recorded& r, FirstCopies&) { r.motor.emplace(m.header.tick, m); }
void keep(const lagrange::plant_rate_t& m, Recorded& r, FirstCopies&) { r.rates.emplace(m.header.tick, m); }
void keep(const lagrange::control_command_t& m, Recorded& r, FirstCopies& seen) {
  if (seen.commands.insert(m.input_position_tick).second) {
    r.commands.push_back(m);
    r.commands_by_tick.emplace(m.header.tick, m);
  }
}

// false if the event is on a channel of this project but does not decode.
bool record(const lcm::LogEvent& ev, Recorded& r, FirstCopies& seen) {
  if (ev.channel == transport::kScenario) {
    if (r.scenario) return true;
    r.scenario = logs::scenarioYaml(ev);
    return r.scenario.has_value();
  }
  return transport::withChannelMessage(ev.channel, true, [&](auto m) {
    if (!logs::decodeEvent(ev, m)) return false;
    keep(m, r, seen);
    return true;
  });
}

std::string show(double x) { return util::exactText(x); }

size_t outputCount(const Recorded& r, const std::string& outputs) {
  if (outputs == transport::kActuatorState) return r.states.size();
  if (outputs == transport::kPlantTruth) return r.truths.size();
  return r.commands.size();
}

}  // namespace

Opened openLog(const std::string& log_path, const std::vector<std::string>& overrides,
               const std::string& outputs) {
  Opened o;
  Recorded& rec = o.rec;
  FirstCopies seen;
  long long undecodable = 0;
  logs::LogScan scan;
  try {
    scan = logs::readLog(log_path,
                         [&](const lcm::LogEvent& ev) { undecodable += record(ev, rec, seen) ? 0 : 1; });
  } catch (const logs::LogError& e) {
    throw ReplayError(e.what());
  }
  // In tick order, which is the order each process computed them in: a copy
  // the logger lacked and the plant had re-sent is in the log a few ticks late.
  const auto by_tick = [](const auto& a, const auto& b) { return a.header.tick < b.header.tick; };
  std::stable_sort(rec.commands.begin(), rec.commands.end(), by_tick);
  std::stable_sort(rec.states.begin(), rec.states.end(), by_tick);
  std::stable_sort(rec.truths.begin(), rec.truths.end(), by_tick);
  ReplayResult& result = o.result;
  result.events = rec.events = scan.events;
  rec.undecodable = undecodable;
  result.warnings = scan.problems();
  if (undecodable > 0)
    result.warnings.push_back(
        std::to_string(undecodable) +
        " events on this project's channels could not be decoded as its messages, or failed "
        "their checksum (corrupted on the way -- the intact copy is re-sent in lockstep -- or "
        "another version's types), and were skipped");
  std::string also;  // what else is wrong with the log, for an error message
  for (const auto& w : result.warnings) also += "; " + w;
  if (!rec.scenario)
    throw ReplayError(log_path + ": no SCENARIO channel among its " + scan.describe() +
                      "; expected a log of a lagrange run (lagrange run writes the scenario first; a stock "
                      "lcm-logger must be started before the scenario to record it)" +
                      also);
  try {
    o.scenario = config::parseScenario(*rec.scenario, log_path + ":SCENARIO", overrides);
  } catch (const config::ConfigError& e) {
    throw ReplayError(std::string("the log's SCENARIO is not a valid scenario: ") + e.what());
  }
  if (outputCount(rec, outputs) == 0)
    throw ReplayError(log_path + ": no " + outputs + " among its " + scan.describe() +
                      ": nothing to compare");
  return o;
}

std::string compare(const std::string& field, const std::vector<double>& recorded,
                    const Eigen::VectorXd& replayed) {
  if (static_cast<Eigen::Index>(recorded.size()) != replayed.size())
    return field + ": recorded " + std::to_string(recorded.size()) + " values, replayed " +
           std::to_string(replayed.size());
  for (size_t i = 0; i < recorded.size(); ++i) {
    const std::string d = compare(field + "[" + std::to_string(i + 1) + "]", recorded[i],
                                  replayed(static_cast<Eigen::Index>(i)));
    if (!d.empty()) return d;
  }
  return "";
}

std::string compare(const std::string& field, double recorded, double replayed) {
  // Bit for bit, not ==: a NaN replayed as the same NaN matches, and -0
  // replayed as +0 is a difference (== says the opposite of both).
  std::uint64_t recorded_bits = 0, replayed_bits = 0;
  std::memcpy(&recorded_bits, &recorded, sizeof recorded);
  std::memcpy(&replayed_bits, &replayed, sizeof replayed);
  if (recorded_bits == replayed_bits) return "";
  const std::string a = show(recorded), b = show(replayed);
  if (a != b) return field + ": recorded " + a + ", replayed " + b;
  // Two NaNs of different payloads (or signs) print alike: their bits say how they differ.
  char bits[96];
  std::snprintf(bits, sizeof bits, " (bits 0x%016llx), replayed %s (bits 0x%016llx)",
                static_cast<unsigned long long>(recorded_bits), b.c_str(),
                static_cast<unsigned long long>(replayed_bits));
  return field + ": recorded " + a + bits;
}

std::string at(int64_t tick, double t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "tick %lld (t = %.6f s): ", static_cast<long long>(tick), t);
  return buf;
}

}  // namespace lagrange::tools::replay_log
