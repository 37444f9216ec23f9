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
#include "config/sensor_models.hpp"

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
      integer("logger_nice", &LockstepConfig::logger_nice, 0, 19, "expected a nice value from 0 to 19"),
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
      {"cpus",
       [](MapReader& rt, RealtimeConfig& c) {
         if (!rt.has("cpus")) return;
         MapReader cpus = rt.map("cpus");
         std::set<std::string> names;
         for (const std::string& name : cpus.keys()) {
           if (name != "plant" && name != "controller" && name != "actuator" && name != "logger")
             cpus.fail(name, "unknown process; expected plant, controller, actuator or logger");
           const YAML::Node list = cpus.child(name);
           const std::string expected = "expected a list of CPU numbers from 0 to 1023, e.g. [1]";
           if (!list.IsSequence() || list.size() == 0) cpus.fail(name, expected);
           std::vector<int> ids;
           for (const auto& item : list) {
             const std::string text = item.IsScalar() ? item.Scalar() : "";
             size_t used = 0;
             int id = -1;
             try {
               id = std::stoi(text, &used);
             } catch (const std::exception&) {
               used = 0;
             }
             if (text.empty() || used != text.size() || id < 0 || id > 1023) cpus.fail(name, expected);
             ids.push_back(id);
           }
           c.cpus[name] = ids;
           names.insert(name);
         }
         cpus.finish(names);
       },
       [](YAML::Emitter& out, const RealtimeConfig& c) {
         if (c.cpus.empty()) return;
         out << YAML::Key << "cpus" << YAML::Value << YAML::BeginMap;
         for (const auto& [name, ids] : c.cpus) out << YAML::Key << name << YAML::Value << YAML::Flow << ids;
         out << YAML::EndMap;
       }},
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
      positive("slow_answer", &SupervisionConfig::slow_answer),
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

void wholeCountsOrZero(MapReader& m, const std::string& key, const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (v(i) < 0.0 || v(i) != std::floor(v(i)))
      m.fail(key, "expected whole numbers >= 0 (0: not quantised), got " + shortNumber(v(i)));
}

auto standardDeviations(const std::string& unit) {
  return [unit](MapReader& m, const std::string& key, const Eigen::VectorXd& v) {
    if ((v.array() < 0.0).any())
      m.fail(key, "expected standard deviations >= 0 [" + unit + "], got " + shortNumber(v.minCoeff()));
  };
}
}  // namespace

// sensors and faults: their own keys beside the maps of sensors and channels.
const Fields<SensorsConfig>& sensorsFields() {
  static const Fields<SensorsConfig> fields = {seed("seed", &SensorsConfig::seed)};
  return fields;
}
const Fields<FaultsConfig>& faultsFields() {
  static const Fields<FaultsConfig> fields = {seed("seed", &FaultsConfig::seed)};
  return fields;
}

namespace {
// A registered sensor model's key (config/sensor_models.hpp): a per-joint
// vector kept in model_params, sized like the sensor's own vectors.
Field<JointSensorConfig> modelKey(const JointVectorKey& k) {
  return {k.key,
          [k](MapReader& m, JointSensorConfig& c) {
            if (m.has(k.key))
              c.model_params[k.key] =
                  m.vector(k.key, static_cast<int>(c.noise_sigma.size()), true, k.positive);
          },
          [k](YAML::Emitter& out, const JointSensorConfig& c) {
            if (const auto it = c.model_params.find(k.key); it != c.model_params.end())
              writeVector(out, k.key, it->second);
          }};
}

// A sensor's own fields, then every registered model's keys (none of which
// is a sensor's own: registerSensorModelKeys refuses those).
Fields<JointSensorConfig> withModelKeys(Fields<JointSensorConfig> fields) {
  for (const SensorModelKeys& model : sensorModelKeys())
    for (const JointVectorKey& k : model.keys) fields.push_back(modelKey(k));
  return fields;
}
}  // namespace

// sensors.position and sensors.motor: angles, quantised, noisy and late.
const Fields<JointSensorConfig>& angleSensorFields() {
  static const Fields<JointSensorConfig> fields = {
      jointVector("counts_per_revolution", &JointSensorConfig::counts_per_revolution,
                  VectorRule().checkedBy(wholeCountsOrZero)),
      jointVector("noise_sigma", &JointSensorConfig::noise_sigma,
                  VectorRule().checkedBy(standardDeviations("rad"))),
      wholeAtLeast("delay", &JointSensorConfig::delay, 0, "expected a whole number of samples >= 0"),
  };
  return fields;
}

// sensors.velocity: rates, noisy and late.
const Fields<JointSensorConfig>& rateSensorFields() {
  static const Fields<JointSensorConfig> fields = {
      jointVector("noise_sigma", &JointSensorConfig::noise_sigma,
                  VectorRule().checkedBy(standardDeviations("rad/s"))),
      wholeAtLeast("delay", &JointSensorConfig::delay, 0, "expected a whole number of samples >= 0"),
  };
  return fields;
}

const Fields<JointSensorConfig>& angleSensorSection() {
  static const Fields<JointSensorConfig> fields = withModelKeys(angleSensorFields());
  return fields;
}
const Fields<JointSensorConfig>& rateSensorSection() {
  static const Fields<JointSensorConfig> fields = withModelKeys(rateSensorFields());
  return fields;
}

// faults.channels.NAME: what may happen to a datagram on one channel.
const Fields<ChannelFaults>& channelFaultFields() {
  static const Fields<ChannelFaults> fields = {
      probability("drop", &ChannelFaults::drop),
      probability("duplicate", &ChannelFaults::duplicate),
      probability("reorder", &ChannelFaults::reorder),
      probability("corrupt", &ChannelFaults::corrupt),
      nonNegative("delay", &ChannelFaults::delay, "expected a time >= 0 [s]"),
      nonNegative("delay_jitter", &ChannelFaults::delay_jitter, "expected a time >= 0 [s]"),
  };
  return fields;
}

// faults.receivers.PROCESS: the share of datagrams a process loses on receipt.
const Fields<ReceiverFaults>& receiverFaultFields() {
  static const Fields<ReceiverFaults> fields = {probability("drop", &ReceiverFaults::drop)};
  return fields;
}

namespace {
// One sensors.<quantity> map, its vectors one entry per joint.
JointSensorConfig readJointSensor(MapReader p, int n, const Fields<JointSensorConfig>& fields) {
  JointSensorConfig c;
  c.counts_per_revolution = Eigen::VectorXd::Zero(n);
  c.noise_sigma = Eigen::VectorXd::Zero(n);
  readFields(p, c, fields);
  // A sensor model acts with all its keys, or not at all.
  for (const SensorModelKeys& model : sensorModelKeys()) {
    std::vector<std::string> given, missing;
    for (const JointVectorKey& k : model.keys)
      (c.model_params.count(k.key) ? given : missing).push_back(k.key);
    if (!given.empty() && !missing.empty())
      p.fail(missing.front(), "missing; sensor model " + model.model + " takes its keys together, and " +
                                  given.front() + " is given");
  }
  return c;
}
}  // namespace

// sensors: the joint-angle sensor between the plant and PLANT_POSITION, the
// velocity sensor (PLANT_RATE) and the motor-angle sensor of flexible joints.
void readSensorsSection(MapReader& root, Scenario& s) {
  if (!root.has("sensors")) return;
  MapReader r = root.map("sensors");
  SensorsConfig c;
  readFieldsAmongOthers(r, c, sensorsFields());
  const int n = s.dof();
  c.position.counts_per_revolution = Eigen::VectorXd::Zero(n);
  c.position.noise_sigma = Eigen::VectorXd::Zero(n);
  if (r.has("position")) c.position = readJointSensor(r.map("position"), n, angleSensorSection());
  if (r.has("velocity")) c.velocity = readJointSensor(r.map("velocity"), n, rateSensorSection());
  if (r.has("motor")) {
    if (!s.flexible)
      r.fail("motor", "a motor-angle sensor needs flexible joints (robot.flexible); this arm is rigid");
    c.motor = readJointSensor(r.map("motor"), n, angleSensorSection());
  }
  r.finish(keysUnder("sensors"));
  s.sensors = c;
}

// faults: seeded fault injection per channel (sending side) and per
// receiving process.
void readFaultsSection(MapReader& root, Scenario& s) {
  if (!root.has("faults")) return;
  MapReader f = root.map("faults");
  readFieldsAmongOthers(f, s.faults, faultsFields());
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
      // Faults are injected by the built-in processes' nodes as they publish
      // and receive: a program from outside injects none.
      const bool plants = name == "all" || name.rfind("PLANT_", 0) == 0;
      if (s.plant.external() && plants)
        channels.fail(name,
                      "faults on the plant's channels are injected by the built-in plant, and plant.type "
                      "is external; expected faults on CONTROL_COMMAND, ACTUATOR_STATE, STATUS or "
                      "SCENARIO only");
      names.insert(name);
      ChannelFaults rule;
      readFields(channels.map(name), rule, channelFaultFields());
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
      if (name == "plant" && s.plant.external())
        receivers.fail(name,
                       "is injected by the built-in plant, and plant.type is external; expected it left out");
      names.insert(name);
      ReceiverFaults r;
      readFields(receivers.map(name), r, receiverFaultFields());
      s.faults.receiver_drop[name] = r.drop;
    }
    receivers.finish(names);
  }
  f.finish(keysUnder("faults"));
}

}  // namespace lagrange::config::sections
