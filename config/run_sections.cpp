/// @file
/// How the run is judged and carried out: metrics, lockstep, realtime,
/// supervision, faults (config/scenario_sections.hpp).

#include <set>

#include "config/scenario_sections.hpp"

namespace lagrange::config::sections {

// metrics: what counts as converged.
void readMetricsSection(MapReader& root, Scenario& s) {
  if (!root.has("metrics")) return;
  MapReader m = root.map("metrics");
  s.metrics.tolerance = m.positive("tolerance", s.metrics.tolerance);
  s.metrics.convergence_deadline = m.positive("convergence_deadline", s.metrics.convergence_deadline);
  s.metrics.xi_tolerance = m.positive("xi_tolerance", s.metrics.xi_tolerance);
  m.finish({"tolerance", "convergence_deadline", "xi_tolerance"});
}

// lockstep: re-send timing and the logger's window.
void readLockstepSection(MapReader& root, Scenario& s) {
  if (!root.has("lockstep")) return;
  MapReader l = root.map("lockstep");
  s.lockstep.retransmit_timeout = l.positive("retransmit_timeout", s.lockstep.retransmit_timeout);
  s.lockstep.logger_window = l.integer("logger_window", s.lockstep.logger_window);
  if (s.lockstep.logger_window < 1) l.fail("logger_window", "expected a whole number >= 1");
  l.finish({"retransmit_timeout", "logger_window"});
}

// realtime: stale-torque policy, input ages, scheduling.
void readRealtimeSection(MapReader& root, Scenario& s) {
  if (!root.has("realtime")) return;
  MapReader r = root.map("realtime");
  s.realtime.max_torque_age = r.integer("max_torque_age", s.realtime.max_torque_age);
  if (s.realtime.max_torque_age < 1) r.fail("max_torque_age", "expected a whole number of periods >= 1");
  s.realtime.stale_torque = r.choice("stale_torque", kStaleTorqueNames, "policy", s.realtime.stale_torque);
  s.realtime.hold_periods = r.integer("hold_periods", s.realtime.hold_periods);
  if (s.realtime.hold_periods < 0) r.fail("hold_periods", "expected a whole number >= 0");
  s.realtime.max_input_age = r.positive("max_input_age", s.realtime.max_input_age);
  s.realtime.priority = r.integer("priority", s.realtime.priority);
  if (s.realtime.priority < 0 || s.realtime.priority > 99)
    r.fail("priority", "expected a SCHED_FIFO priority from 1 to 99, or 0 for the normal scheduler");
  r.finish({"max_torque_age", "stale_torque", "hold_periods", "max_input_age", "priority"});
}

// supervision: which processes are restarted when they die.
void readSupervisionSection(MapReader& root, Scenario& s) {
  if (!root.has("supervision")) return;
  MapReader sv = root.map("supervision");
  if (sv.has("restart")) {
    const YAML::Node list = sv.child("restart");
    if (!list.IsSequence())
      sv.fail("restart", "expected a list of processes to restart when they die, e.g. [controller]");
    for (const auto& item : list) {
      const std::string name = item.IsScalar() ? item.as<std::string>() : "";
      if (name != "controller" && name != "actuator")
        sv.fail("restart",
                "cannot restart '" + name +
                    "'; expected controller and/or actuator (the plant holds the simulated arm, the "
                    "logger the log)");
      if (!s.supervision.restarts(name)) s.supervision.restart.push_back(name);
    }
  }
  s.supervision.max_restarts = sv.integer("max_restarts", s.supervision.max_restarts);
  if (s.supervision.max_restarts < 0) sv.fail("max_restarts", "expected a whole number >= 0");
  sv.finish({"restart", "max_restarts"});
}

namespace {
double probability(MapReader& map, const char* key) {
  const double p = map.number(key, 0.0);
  if (p < 0.0 || p > 1.0) map.fail(key, "expected a probability from 0 to 1");
  return p;
}
}  // namespace

// faults: seeded fault injection per channel (sending side) and per
// receiving process.
void readFaultsSection(MapReader& root, Scenario& s) {
  if (!root.has("faults")) return;
  MapReader f = root.map("faults");
  const int seed = f.integer("seed", static_cast<int>(s.faults.seed));
  if (seed < 0) f.fail("seed", "expected a whole number >= 0");
  s.faults.seed = static_cast<uint64_t>(seed);
  if (f.has("channels")) {
    MapReader channels = f.map("channels");
    const std::set<std::string> known = {"all",         "PLANT_POSITION",  "PLANT_TRUTH",
                                         "PLANT_MOTOR", "CONTROL_COMMAND", "ACTUATOR_STATE",
                                         "STATUS",      "SCENARIO"};
    std::set<std::string> names;
    for (const std::string& name : channels.keys()) {
      if (known.count(name) == 0)
        channels.fail(name,
                      "unknown channel; expected all, PLANT_POSITION, PLANT_TRUTH, PLANT_MOTOR, "
                      "CONTROL_COMMAND, ACTUATOR_STATE, STATUS or SCENARIO");
      names.insert(name);
      MapReader c = channels.map(name);
      ChannelFaults rule;
      rule.drop = probability(c, "drop");
      rule.duplicate = probability(c, "duplicate");
      rule.reorder = probability(c, "reorder");
      rule.corrupt = probability(c, "corrupt");
      rule.delay = c.number("delay", 0.0);
      if (rule.delay < 0.0) c.fail("delay", "expected a time >= 0 [s]");
      rule.delay_jitter = c.number("delay_jitter", 0.0);
      if (rule.delay_jitter < 0.0) c.fail("delay_jitter", "expected a time >= 0 [s]");
      c.finish({"drop", "duplicate", "reorder", "corrupt", "delay", "delay_jitter"});
      s.faults.channels[name] = rule;
    }
    channels.finish(names);
  }
  if (f.has("receivers")) {
    MapReader receivers = f.map("receivers");
    std::set<std::string> names;
    for (const std::string& name : receivers.keys()) {
      if (name != "plant" && name != "controller" && name != "actuator" && name != "logger")
        receivers.fail(name, "unknown process; expected plant, controller, actuator or logger");
      names.insert(name);
      MapReader r = receivers.map(name);
      s.faults.receiver_drop[name] = probability(r, "drop");
      r.finish({"drop"});
    }
    receivers.finish(names);
  }
  f.finish({"seed", "channels", "receivers"});
}

}  // namespace lagrange::config::sections
