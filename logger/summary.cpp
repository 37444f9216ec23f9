#include "logger/summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "controller/gain_report_json.hpp"
#include "controller/paper_section.hpp"
#include "logger/verdict.hpp"
#include "model/urdf_arm.hpp"

namespace lagrange::logger {

namespace {
// A figure nothing measured is null, never a number that reads as perfect
// (a program from outside reports NaN for what it does not measure).
nlohmann::json measured(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

// name: the paper's printed number; paper_label: its LaTeX source's label (null: not numbered).
nlohmann::json conditionJson(const model::ConditionReport& c) {
  const std::string label = model::paperLabel(c.name);
  return {{"name", c.name},
          {"paper_label", label.empty() ? nlohmann::json() : nlohmann::json(label)},
          {"expression", c.expression},
          {"lhs", c.lhs},
          {"rhs", c.rhs},
          {"holds", c.holds},
          {"margin", c.margin()}};
}

// gains: the controller's stability conditions and the constants they rest on.
nlohmann::json gainsJson(const controller::GainReport& g) {
  using nlohmann::json;
  if (g.unchecked) return {{"checked", false}, {"why", *g.unchecked}};
  json j = {
      {"checked", true},
      {"condition", g.condition.name},
      {"expression", g.condition.expression},
      {"lhs", g.condition.lhs},
      {"rhs", g.condition.rhs},
      {"condition_holds", g.holds()},
      {"margin", g.margin()},
      {"binding_condition", g.binding().name},
      {"k_c", g.kc},
      {"k_c_method", g.kc_proven ? "proven: closed-form Christoffel symbols"
                                 : "estimate: largest ratio found (no closed form of C)"},
      {"k_c_largest_found", g.kc_found},
      {"k_delta", g.kdelta},
      {"k_delta_method", g.kdelta_exact ? "closed form" : "estimate: sampled supremum x 1.02"},
  };
  json conditions = json::array({conditionJson(g.condition)});
  for (const auto& c : g.chain) conditions.push_back(conditionJson(c));
  j["conditions"] = conditions;
  if (g.eta)
    j["eta"] = {{"eta1", g.eta->eta1},
                {"eta2", g.eta->eta2},
                {"eta3", g.eta->eta3},
                {"method", "estimate: eta1, eta2 sampled suprema refined by local ascent; eta3 exact"}};
  if (!g.proposition.empty()) {
    json proposition = json::array();
    for (const auto& c : g.proposition) proposition.push_back(conditionJson(c));
    j["proposition1"] = proposition;
    j["proposition1_holds"] = g.propositionHolds();
  }
  if (!g.warnings.empty()) j["warnings"] = g.warnings;
  const controller::SampledDataCheck& sd = g.sampled;
  j["sampled_data"] = {
      {"rate", sd.rate},
      {"verdict", sd.verdict},
      {"why", sd.why},
      {"spectral_radius", sd.spectral_radius},
      {"worst_time", sd.worst_time},
      {"sampled_decay", sd.sampled_decay},
      {"continuous_decay", sd.continuous_decay},
      {"fastest_mode", sd.fastest_mode},
      {"fastest_mode_times_period", sd.fastestModeTimesPeriod()},
      {"sufficient_rate", sd.sufficient_rate ? json(*sd.sufficient_rate) : json(nullptr)},
      {"one_period_delay", sd.one_period_delay},
      {"method", "estimate: the discretised closed loop linearised along the reference"},
  };
  // `lagrange run --check-sampled`: the loop simulated against a fine-rate one.
  if (g.simulated) j["sampled_simulation"] = controller::sampledSimulationJson(*g.simulated);
  return j;
}
}  // namespace

namespace {
// What the plant has that the controllers' model has not (summary.json plant).
nlohmann::json plantJson(const config::Scenario& s) {
  using nlohmann::json;
  json out = json::object();
  const config::PlantConfig& p = s.plant;
  auto vec = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  if (p.engine != "ode") {  // the design's engine goes unsaid, as in config.resolved.yaml
    out["engine"] = p.engine;
    if (p.engine == "mujoco")
      out["mujoco_integrator"] = util::nameOf(config::kMujocoIntegratorNames, p.mujoco_integrator);
  }
  if (p.joint_damping) out["joint_damping"] = vec(*p.joint_damping);
  if (p.joint_friction) out["joint_friction"] = vec(*p.joint_friction);
  if (p.rotor_damping) out["rotor_damping"] = vec(*p.rotor_damping);
  if (p.rotor_friction) out["rotor_friction"] = vec(*p.rotor_friction);
  if (p.urdf_dynamics) out["urdf_dynamics"] = true;
  if (p.joint_limits) out["joint_limits"] = true;
  if (p.payload) out["payload"] = {{"mass", p.payload->mass}, {"com", vec(p.payload->com)}};
  if (p.model_error)
    out["model_error"] = {{"mass", p.model_error->mass},
                          {"inertia", p.model_error->inertia},
                          {"com", p.model_error->com},
                          {"seed", p.model_error->seed}};
  if (p.payload || p.model_error) {
    const std::vector<model::LinkChange> changes =
        s.urdf_model ? model::perturbedBodies(*s.urdf_model, p.payload, p.model_error).changes
                     : model::perturbedChain(s.robot, p.payload, p.model_error).changes;
    json links = json::array();
    for (const model::LinkChange& c : changes)
      links.push_back({{"link", c.link},
                       {"mass", {{"nominal", c.nominal_mass}, {"plant", c.mass}}},
                       {"inertia_scale", c.inertia_scale},
                       {"com", {{"nominal", vec(c.nominal_com)}, {"plant", vec(c.com)}}}});
    out["links"] = links;
  }
  return out;
}
}  // namespace

void watchLimits(TrackingMetrics& metrics, const config::Scenario& s) {
  if (s.actuator.saturation) metrics.watchSaturation(*s.actuator.saturation);
  if (!s.urdf_model) return;
  const auto& joints = s.urdf_model->jointProperties();
  Eigen::VectorXd limits = Eigen::VectorXd::Constant(s.dof(), std::numeric_limits<double>::infinity());
  bool any = false;
  for (size_t i = 0; i < joints.size(); ++i)
    if (joints[i].velocity) {
      limits(static_cast<Eigen::Index>(i)) = *joints[i].velocity;
      any = true;
    }
  if (any) metrics.watchVelocities(s.urdf_model->jointNames(), limits);
}

nlohmann::json makeSummary(const config::Scenario& s, const TrackingSummary& t,
                           const controller::GainReport& g, const RunFacts& f) {
  using nlohmann::json;
  json j;
  j["scenario"] = s.name;
  j["mode"] = config::toString(s.mode);
  j["controller"] = {{"type", s.controller.type}};
  for (const auto& [key, v] : s.controller.params)  // a registered type's keys
    j["controller"][key] = std::vector<double>(v.data(), v.data() + v.size());
  if (s.controller.type == "flexible") {
    const controller::PaperSettings& c = controller::paperSettings(s);
    if (c.motor_rate)
      j["controller"]["motor_rate"] = util::nameOf(controller::kMotorRateNames, *c.motor_rate);
    if (c.motor_rate == controller::MotorRate::kFiltered)
      j["controller"]["motor_rate_pole"] =
          std::vector<double>(c.motor_rate_pole.data(), c.motor_rate_pole.data() + c.motor_rate_pole.size());
  }
  j["status"] = f.status;
  // With no sample the tracking figures are unknown, not the zero a fresh
  // summary holds; `span` says which stretch of the run they cover.
  const bool sampled = t.samples > 0;
  const auto figure = [sampled](double v) { return sampled ? measured(v) : nlohmann::json(); };
  j["tracking"] = {
      {"tolerance", t.tolerance},
      {"final_error", figure(t.final_error)},
      {"max_error", figure(t.max_error)},
      {"max_error_time", figure(t.max_error_time)},
      {"initial_error", figure(t.initial_error)},
      {"convergence_time", t.convergence_time ? json(*t.convergence_time) : json(nullptr)},
      {"rms_last_second", figure(t.rms_last_second)},
      {"convergence_deadline", s.metrics.convergence_deadline},
      {"met",
       [&] {
         auto by_deadline = [&](const std::optional<double>& ct) {
           return ct.has_value() && *ct <= s.metrics.convergence_deadline;
         };
         bool met = by_deadline(t.convergence_time);
         for (const auto& c : t.chain) met = met && by_deadline(c.convergence_time);
         return met;
       }()},
      {"samples", t.samples},
      {"span",
       {{"from", figure(t.first_time)},
        {"to", figure(t.sim_time)},
        {"of", s.duration},
        {"whole_run", sampled && t.sim_time >= s.lastTick() * s.tickPeriod() - 0.5 * s.tickPeriod()}}},
  };
  if (!t.chain.empty()) {
    json chain = json::array();
    for (size_t i = 0; i < t.chain.size(); ++i) {
      const auto& c = t.chain[i];
      chain.push_back({{"stage", i + 1},
                       {"tolerance", c.tolerance},
                       {"final_error", c.final_error},
                       {"max_error", c.max_error},
                       {"convergence_time", c.convergence_time ? json(*c.convergence_time) : json(nullptr)}});
    }
    j["tracking"]["chain"] = chain;
  }
  if (t.velocity_crossings) {
    json crossed = json::array();
    for (const VelocityCrossing& c : *t.velocity_crossings)
      crossed.push_back({{"joint", c.joint},
                         {"limit", c.limit},
                         {"largest", c.largest},
                         {"first_time", c.first_time},
                         {"samples", c.samples}});
    j["limits"] = {{"velocity", crossed}};
  }
  if (json plant = plantJson(s); !plant.empty()) j["plant"] = plant;
  j["torque"] = {{"max_abs", t.max_abs_torque},
                 {"total_variation", t.torque_total_variation},
                 {"energy", t.control_energy},
                 {"saturated_fraction", t.saturated_fraction ? json(*t.saturated_fraction) : json(nullptr)}};
  j["gains"] = gainsJson(g);
  j["run_id"] = f.run_id;
  j["lagrange_version"] = LAGRANGE_VERSION;  // the programs' version (CMakeLists.txt's project VERSION)
  j["timing"] = {
      {"sim_time", t.sim_time},
      {"wall_time", f.wall_time},
      {"realtime_factor", f.wall_time > 0.0 ? json(t.sim_time / f.wall_time) : json(nullptr)},
      {"publish_rate", s.plant.publish_rate},
  };
  if (s.mode == config::Mode::kLockstep) j["timing"]["logger_nice"] = f.nice;
  json messages = json::object();
  json processes = json::object();
  for (const auto& [name, st] : f.final_status) {
    json channels = json::object();
    for (const auto& c : st.channels) {
      const json reasons = {{"undecodable", c.rejected_undecodable},
                            {"other_run", c.rejected_other_run},
                            {"wrong_publisher", c.rejected_wrong_publisher},
                            {"old_or_repeated", c.rejected_old_or_repeated},
                            {"invalid", c.rejected_invalid},
                            {"corrupt", c.rejected_corrupt},
                            {"unauthenticated", c.rejected_unauthenticated}};
      channels[c.channel] = {{"published", c.published},
                             {"received", c.received},
                             {"rejected", c.rejected},
                             {"rejected_by_reason", reasons}};
      json& total = messages[c.channel];
      if (total.is_null())
        total = {{"published", 0},
                 {"received", 0},
                 {"rejected", 0},
                 {"rejected_by_reason", json::object()},
                 {"injected", json::object()}};
      total["published"] = total["published"].get<long long>() + c.published;
      total["received"] = total["received"].get<long long>() + c.received;
      total["rejected"] = total["rejected"].get<long long>() + c.rejected;
      const json injected = {
          {"dropped", c.injected_dropped},     {"duplicated", c.injected_duplicated},
          {"reordered", c.injected_reordered}, {"delayed", c.injected_delayed},
          {"corrupted", c.injected_corrupted}, {"lost_on_receive", c.injected_lost_on_receive}};
      channels[c.channel]["injected"] = injected;
      for (const auto& [fault, n] : injected.items())
        total["injected"][fault] = total["injected"].value(fault, 0LL) + n.get<long long>();
      for (const auto& [reason, n] : reasons.items())
        total["rejected_by_reason"][reason] =
            total["rejected_by_reason"].value(reason, 0LL) + n.get<long long>();
    }
    processes[name] = {
        {"state", st.state}, {"last_tick", st.last_tick}, {"message", st.message}, {"channels", channels}};
  }
  // A program from outside reports no counts of its own: what it published
  // is what reached its receivers -- the most any of them received. (The
  // channels are transport/channels.hpp's, a layer down.)
  std::vector<const char*> external_channels;
  if (s.controller.type == "external") external_channels.push_back("CONTROL_COMMAND");
  if (s.plant.external())
    for (const char* channel : {"PLANT_POSITION", "PLANT_TRUTH"}) external_channels.push_back(channel);
  for (const char* channel : external_channels) {
    if (!messages.contains(channel) || messages[channel]["published"].get<long long>() != 0) continue;
    long long heard = 0;
    for (const auto& [name, p] : processes.items())
      if (p["channels"].contains(channel))
        heard = std::max(heard, p["channels"][channel]["received"].get<long long>());
    messages[channel]["published"] = heard;
    messages[channel]["published_counted_by"] =
        "its receivers (a program from outside reports no counts): the most any of them received";
  }
  if (s.mode == config::Mode::kRealtime) {
    json loops = json::object();
    json stale = json::object();
    for (const auto& [name, st] : f.final_status) {
      const auto& l = st.loop;
      if (l.cycles == 0) continue;
      loops[name] = {
          {"period", l.period},
          {"scheduler", l.scheduler},
          {"cycles", l.cycles},
          {"achieved_rate", l.achieved_rate},
          {"jitter", {{"p50", l.jitter_p50}, {"p99", l.jitter_p99}, {"max", l.jitter_max}}},
          {"deadline_misses", l.deadline_misses},
          {"on_time_fraction", 1.0 - static_cast<double>(l.deadline_misses) / static_cast<double>(l.cycles)},
          {"longest_miss_run", l.longest_miss_run},
          {"input_age",
           {{"p50", measured(l.input_age_p50)},
            {"p99", measured(l.input_age_p99)},
            {"max", measured(l.input_age_max)}}},
      };
      stale[name] = {{"missing_inputs", l.missing_inputs}, {"stale_inputs", l.stale_inputs}};
      if (name == "plant") {
        j["timing"]["latency"] = {{"p50", measured(l.latency_p50)},
                                  {"p99", measured(l.latency_p99)},
                                  {"max", measured(l.latency_max)}};
        stale[name]["torque_held"] = l.torque_held;
        stale[name]["torque_zeroed"] = l.torque_zeroed;
      }
    }
    if (!f.external_controller_loop.is_null() && !loops.contains("controller"))
      loops["controller"] = f.external_controller_loop;
    j["timing"]["loops"] = loops;
    messages["stale"] = stale;
  }
  j["messages"] = messages;
  j["processes"] = processes;
  if (!f.answers.is_null()) j["answers"] = f.answers;  // LCM modes: the logger timed them
  j["log"] = {
      {"path", f.log_path},
      {"events", f.log_events},
      // ticks up to the newest sample without a PLANT_TRUTH in the log
      {"missing_samples",
       t.samples == 0 ? 0LL : std::max(0LL, std::llround(t.sim_time / s.tickPeriod()) + 1 - t.samples)},
      {"missing_ticks", f.missing_ticks}};
  // Whether the log holds every message the run's processes published (as
  // far as their sequence numbers and last STATUS tell): a reader can trust
  // an analysis of it only then. An in-process run writes every message.
  long long missing = 0;
  for (const auto& [channel, n] : f.missing_records) missing += n;
  j["log"]["missing_records"] = f.missing_records;
  j["log"]["not_recorded"] = f.not_recorded;
  j["log"]["complete"] = missing == 0;
  j["log"]["incomplete_because"] =
      missing == 0 ? json(nullptr)
                   : json(std::to_string(missing) +
                          " messages the run's processes published are not in the log (per channel in "
                          "log.missing_records): the logger did not receive them -- lost on the way, or "
                          "sent while the logger was not reading (stopped, overloaded) and dropped");
  j["verdict"] = runVerdict(j);
  return j;
}

}  // namespace lagrange::logger
