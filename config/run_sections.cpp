/// @file
/// How the run is judged and carried out: metrics, lockstep, realtime,
/// supervision, faults, sensors (config/scenario_sections.hpp).

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "config/key_table.hpp"
#include "config/scenario_sections.hpp"

namespace lagrange::config::sections {

using namespace field;
constexpr int kNoLimit = std::numeric_limits<int>::max();

// metrics: what counts as converged.
const Fields<MetricsConfig>& metricsFields() {
  static const Fields<MetricsConfig> fields = {
      positive("tolerance", &MetricsConfig::tolerance),
      positive("convergence_deadline", &MetricsConfig::convergence_deadline),
      positive("xi_tolerance", &MetricsConfig::xi_tolerance),
  };
  return fields;
}

// lockstep: re-send timing, the logger's window, how long a wait may last.
const Fields<LockstepConfig>& lockstepFields() {
  static const Fields<LockstepConfig> fields = {
      positive("retransmit_timeout", &LockstepConfig::retransmit_timeout),
      integer("logger_window", &LockstepConfig::logger_window, 1, kNoLimit, "expected a whole number >= 1"),
      positive("stall_timeout", &LockstepConfig::stall_timeout),
  };
  return fields;
}

// realtime: stale-torque policy, input ages, scheduling.
const Fields<RealtimeConfig>& realtimeFields() {
  static const Fields<RealtimeConfig> fields = {
      integer("max_torque_age", &RealtimeConfig::max_torque_age, 1, kNoLimit,
              "expected a whole number of periods >= 1"),
      choice("stale_torque", &RealtimeConfig::stale_torque, kStaleTorqueNames, "policy"),
      integer("hold_periods", &RealtimeConfig::hold_periods, 0, kNoLimit, "expected a whole number >= 0"),
      positive("max_input_age", &RealtimeConfig::max_input_age),
      integer("priority", &RealtimeConfig::priority, 0, 99,
              "expected a SCHED_FIFO priority from 1 to 99, or 0 for the normal scheduler"),
  };
  return fields;
}

// supervision: which processes are restarted when they die.
const Fields<SupervisionConfig>& supervisionFields() {
  static const Fields<SupervisionConfig> fields = {
      {"restart",
       [](MapReader& sv, SupervisionConfig& c) {
         if (!sv.has("restart")) return;
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
           if (!c.restarts(name)) c.restart.push_back(name);
         }
       },
       [](YAML::Emitter& out, const SupervisionConfig& c) {
         out << YAML::Key << "restart" << YAML::Value << YAML::Flow << c.restart;
       }},
      integer("max_restarts", &SupervisionConfig::max_restarts, 0, kNoLimit, "expected a whole number >= 0"),
  };
  return fields;
}

void readMetricsSection(MapReader& root, Scenario& s) {
  if (root.has("metrics")) readFields(root.map("metrics"), s.metrics, metricsFields());
}
void readLockstepSection(MapReader& root, Scenario& s) {
  if (root.has("lockstep")) readFields(root.map("lockstep"), s.lockstep, lockstepFields());
}
void readRealtimeSection(MapReader& root, Scenario& s) {
  if (root.has("realtime")) readFields(root.map("realtime"), s.realtime, realtimeFields());
}
void readSupervisionSection(MapReader& root, Scenario& s) {
  if (root.has("supervision")) readFields(root.map("supervision"), s.supervision, supervisionFields());
}

namespace {
std::string shortNumber(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

double probability(MapReader& map, const char* key) {
  const double p = map.number(key, 0.0);
  if (p < 0.0 || p > 1.0) map.fail(key, "expected a probability from 0 to 1");
  return p;
}
}  // namespace

namespace {
// One sensors.<quantity> map: counts_per_revolution (angles only), noise_sigma, delay.
JointSensorConfig readJointSensor(MapReader& p, int n, bool angles, const std::set<std::string>& known) {
  JointSensorConfig c;
  c.counts_per_revolution = Eigen::VectorXd::Zero(n);
  c.noise_sigma = Eigen::VectorXd::Zero(n);
  if (angles && p.has("counts_per_revolution")) {
    c.counts_per_revolution = p.vector("counts_per_revolution", n, true, false);
    for (Eigen::Index i = 0; i < n; ++i)
      if (c.counts_per_revolution(i) < 0.0 ||
          c.counts_per_revolution(i) != std::floor(c.counts_per_revolution(i)))
        p.fail("counts_per_revolution", "expected whole numbers >= 0 (0: not quantised), got " +
                                            shortNumber(c.counts_per_revolution(i)));
  }
  if (p.has("noise_sigma")) {
    c.noise_sigma = p.vector("noise_sigma", n, true, false);
    if ((c.noise_sigma.array() < 0.0).any())
      p.fail("noise_sigma", std::string("expected standard deviations >= 0 [") + (angles ? "rad" : "rad/s") +
                                "], got " + shortNumber(c.noise_sigma.minCoeff()));
  }
  c.delay = p.integer("delay", 0);
  if (c.delay < 0) p.fail("delay", "expected a whole number of samples >= 0, got " + std::to_string(c.delay));
  p.finish(known);
  return c;
}
}  // namespace

// sensors: the joint-angle sensor between the plant and PLANT_POSITION, the
// velocity sensor (PLANT_RATE) and the motor-angle sensor of flexible joints.
void readSensorsSection(MapReader& root, Scenario& s) {
  if (!root.has("sensors")) return;
  MapReader r = root.map("sensors");
  SensorsConfig c;
  const int seed = r.integer("seed", 1);
  if (seed < 0) r.fail("seed", "expected a whole number >= 0");
  c.seed = static_cast<uint64_t>(seed);
  const int n = s.dof();
  c.position.counts_per_revolution = Eigen::VectorXd::Zero(n);
  c.position.noise_sigma = Eigen::VectorXd::Zero(n);
  if (r.has("position")) {
    MapReader p = r.map("position");
    c.position = readJointSensor(p, n, true, keysUnder("sensors.position"));
  }
  if (r.has("velocity")) {
    MapReader v = r.map("velocity");
    c.velocity = readJointSensor(v, n, false, keysUnder("sensors.velocity"));
  }
  if (r.has("motor")) {
    if (!s.flexible)
      r.fail("motor", "a motor-angle sensor needs flexible joints (robot.flexible); this arm is rigid");
    MapReader m = r.map("motor");
    c.motor = readJointSensor(m, n, true, keysUnder("sensors.motor"));
  }
  r.finish(keysUnder("sensors"));
  s.sensors = c;
}

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
    // The channels of transport/channels.hpp a fault can be injected on (config
    // sits below transport), and "all".
    const std::vector<std::string> known = {"all",        "PLANT_POSITION",  "PLANT_TRUTH",    "PLANT_MOTOR",
                                            "PLANT_RATE", "CONTROL_COMMAND", "ACTUATOR_STATE", "STATUS",
                                            "SCENARIO"};
    std::set<std::string> names;
    for (const std::string& name : channels.keys()) {
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        std::string list;
        for (size_t i = 0; i < known.size(); ++i)
          list += (i == 0 ? "" : i + 1 == known.size() ? " or " : ", ") + known[i];
        channels.fail(name, "unknown channel; expected " + list);
      }
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
      c.finish(keysUnder("faults.channels.NAME"));
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
      r.finish(keysUnder("faults.receivers.PROCESS"));
    }
    receivers.finish(names);
  }
  f.finish(keysUnder("faults"));
}

}  // namespace lagrange::config::sections
