#include "tools/replay/replay_log.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>
#include <set>

#include "logs/log_reader.hpp"
#include "transport/channels.hpp"
#include "transport/message_auth.hpp"
#include "transport/safe_decode.hpp"
#include "util/number_text.hpp"

namespace lagrange::tools::replay_log {

namespace {

// Keeps the first copy of each tick (lockstep re-sends are identical).
struct FirstCopies {
  std::set<int64_t> commands, states, truths;
};

// Where each message type goes: every position, rate and motor sample by tick; the
// first copy of each truth, actuator state and command in order too. True if kept.
bool keep(const lagrange::plant_position_t& m, Recorded& r, FirstCopies&) {
  return r.positions.emplace(m.header.tick, m).second;
}
bool keep(const lagrange::plant_truth_t& m, Recorded& r, FirstCopies& seen) {
  if (!seen.truths.insert(m.header.tick).second) return false;
  r.truths.push_back(m);
  return true;
}
bool keep(const lagrange::actuator_state_t& m, Recorded& r, FirstCopies& seen) {
  if (!seen.states.insert(m.header.tick).second) return false;
  r.actuator.emplace(m.header.tick, m);
  r.states.push_back(m);
  return true;
}
bool keep(const lagrange::plant_motor_t& m, Recorded& r, FirstCopies&) {
  return r.motor.emplace(m.header.tick, m).second;
}
bool keep(const lagrange::plant_rate_t& m, Recorded& r, FirstCopies&) {
  return r.rates.emplace(m.header.tick, m).second;
}
bool keep(const lagrange::control_command_t& m, Recorded& r, FirstCopies& seen) {
  if (!seen.commands.insert(m.input_position_tick).second) return false;
  r.commands.push_back(m);
  r.commands_by_tick.emplace(m.header.tick, m);
  return true;
}

// What is wrong with an event that logs::decodeEvent refused: it decodes
// (with or without a stock logger's MAC trailer) but fails its checksum, or
// it does not decode at all.
template <class Msg>
DamagedEvent diagnose(const lcm::LogEvent& ev, long long offset, Msg& m) {
  DamagedEvent d{ev.channel, offset, std::nullopt, ""};
  const auto size = static_cast<std::size_t>(std::max<int32_t>(ev.datalen, 0));
  if (transport::safeDecode(ev.data, size, m) ||
      (size > transport::kMacBytes && transport::safeDecode(ev.data, size - transport::kMacBytes, m))) {
    d.tick = m.header.tick;
    d.why = "fails its checksum (its bytes changed after it was sent)";
  } else {
    d.why = "does not decode as " + std::string(Msg::getTypeName()) + " (" + std::to_string(size) + " bytes)";
  }
  return d;
}

// false if the event is on a channel of this project but cannot be used.
bool record(const lcm::LogEvent& ev, long long offset, Recorded& r, FirstCopies& seen) {
  if (ev.channel == transport::kScenario) {
    if (r.scenario) return true;
    r.scenario = logs::scenarioYaml(ev);
    return r.scenario.has_value();
  }
  if (const std::string meant = channelOneByteFrom(ev.channel); !meant.empty()) {
    r.damage.events.push_back(
        {meant, offset, std::nullopt,
         "is on channel '" + ev.channel + "', one byte from " + meant + " (a damaged channel name)"});
    return false;
  }
  return transport::withChannelMessage(ev.channel, true, [&](auto m) {
    if (!logs::decodeEvent(ev, m)) {
      r.damage.events.push_back(diagnose(ev, offset, m));
      return false;
    }
    if (keep(m, r, seen)) r.offsets[ev.channel].emplace(m.header.tick, offset);
    return true;
  });
}

std::string show(double x) { return util::exactText(x); }

size_t outputCount(const Recorded& r, const std::string& outputs) {
  if (outputs == transport::kActuatorState) return r.states.size();
  if (outputs == transport::kPlantTruth) return r.truths.size();
  return r.commands.size();
}

// The log's SCENARIO, parsed as recorded and as --set changes it.
void parseScenarios(Opened& o, const std::string& log_path, const std::vector<std::string>& overrides) {
  const std::string source = log_path + ":SCENARIO";
  try {
    const config::Scenario logged = config::parseLoggedScenario(*o.rec.scenario, source);
    o.logged_shape = shapeOf(logged);
    o.logged_mode = logged.mode;
    if (overrides.empty()) o.scenario = logged;
  } catch (const config::ConfigError& e) {
    throw ReplayError(std::string("the log's SCENARIO is not a valid scenario: ") + e.what());
  }
  if (overrides.empty()) return;
  try {
    o.scenario = config::parseLoggedScenario(*o.rec.scenario, source, overrides);
  } catch (const config::ConfigError& e) {
    throw ReplayError(std::string("the log's SCENARIO changed by --set is not a valid scenario: ") +
                      e.what());
  }
}

}  // namespace

Opened openLog(const std::string& log_path, const std::vector<std::string>& overrides,
               const std::string& outputs) {
  Opened o;
  Recorded& rec = o.rec;
  FirstCopies seen;
  long long undecodable = 0;
  try {
    logs::LogEventReader reader(log_path);
    // No event larger than its channel's messages can be in this log's own
    // scenario is read (logs/event_bounds.hpp): a 241 MB ACTUATOR_STATE
    // would take replay to gigabytes.
    reader.limitEvents(logs::boundsOfLog(log_path));
    long long whole_events_bytes = 0;  // of the events before this one: with the bytes skipped, its offset
    long long skipped = 0;
    while (const lcm::LogEvent* ev = reader.next()) {
      const long long offset = whole_events_bytes + reader.scan().skipped_bytes +
                               reader.scan().oversized_bytes + reader.scan().outside_run_bytes;
      if (reader.scan().skipped_bytes > skipped) {  // a stretch ending where this event starts
        const long long bytes = reader.scan().skipped_bytes - skipped;
        rec.damage.skipped.push_back({offset - bytes, bytes});
        skipped = reader.scan().skipped_bytes;
      }
      whole_events_bytes +=
          logs::log_format::kHeaderBytes + static_cast<long long>(ev->channel.size()) + ev->datalen;
      undecodable += record(*ev, offset, rec, seen) ? 0 : 1;
    }
    rec.scan = reader.scan();
    for (const logs::OversizedEvent& big : rec.scan.first_oversized)
      rec.damage.events.push_back(
          {big.channel, big.offset, big.tick >= 0 ? std::optional<int64_t>(big.tick) : std::nullopt,
           "is " + std::to_string(big.bytes) + " bytes, more than any of its messages can be in this log (" +
               std::to_string(big.bound) + "): skipped unread"});
    for (const logs::OversizedEvent& stray : rec.scan.first_outside)
      rec.damage.events.push_back({stray.channel, stray.offset, stray.tick,
                                   "names tick " + std::to_string(stray.tick) + ", outside the run's 0 to " +
                                       std::to_string(stray.bound) + " (a damaged tick field?): dropped"});
  } catch (const logs::LogError& e) {
    throw ReplayError(e.what());
  }
  const logs::LogScan& scan = rec.scan;
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
  if (!rec.damage.events.empty()) result.warnings.push_back(describe(rec.damage));
  if (undecodable > static_cast<long long>(rec.damage.events.size()))
    result.warnings.push_back("the SCENARIO event does not decode as lagrange.scenario_t");
  std::string also;  // what else is wrong with the log, for an error message
  for (const auto& w : result.warnings) also += "; " + w;
  if (!rec.scenario)
    throw ReplayError(log_path + ": no SCENARIO channel among its " + scan.describe() +
                      "; expected a log of a lagrange run (lagrange run writes the scenario first; a stock "
                      "lcm-logger must be started before the scenario to record it)" +
                      also);
  parseScenarios(o, log_path, overrides);
  if (outputCount(rec, outputs) == 0)
    throw ReplayError(log_path + ": no " + outputs + " among its " + scan.describe() +
                      ": nothing to compare" + also);
  return o;
}

std::string whyLacking(const Recorded& rec, const std::string& channel, int64_t from, int64_t to) {
  // Where the ticks would be: after the copy of the tick before them, and
  // before the copies a few ticks after (a re-sent copy lands a few ticks late).
  long long lower = 0, upper = std::numeric_limits<long long>::max();
  if (const auto it = rec.offsets.find(channel); it != rec.offsets.end()) {
    const std::map<int64_t, long long>& offsets = it->second;
    if (auto below = offsets.lower_bound(from); below != offsets.begin()) lower = std::prev(below)->second;
    // Saturated: a crafted tick near INT64_MAX must not overflow.
    const int64_t past =
        to > std::numeric_limits<int64_t>::max() - 3 ? std::numeric_limits<int64_t>::max() : to + 3;
    if (auto above = offsets.upper_bound(past); above != offsets.end()) upper = above->second;
  }
  return whatMayHaveHeld(rec.damage, channel, from, to, lower, upper);
}

std::string whereIs(const Recorded& rec, const std::string& channel, int64_t tick) {
  const auto by_channel = rec.offsets.find(channel);
  if (by_channel == rec.offsets.end()) return "";
  const auto it = by_channel->second.find(tick);
  return it == by_channel->second.end() ? "" : "the event at byte " + std::to_string(it->second);
}

void requireTaken(Eigen::Index rows, Eigen::Index columns, Eigen::Index expected_rows,
                  Eigen::Index expected_columns, const std::string& what) {
  if (rows == expected_rows && columns == expected_columns) return;
  throw ReplayError(what + " is " + std::to_string(rows) + " x " + std::to_string(columns) +
                    ", as the log's SCENARIO gives it; the scenario changed by --set takes " +
                    std::to_string(expected_rows) + " x " + std::to_string(expected_columns) +
                    ": the log's inputs do not fit the changed scenario");
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
