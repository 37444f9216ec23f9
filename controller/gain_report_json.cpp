#include "controller/gain_report_json.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "config/input_file.hpp"
#include "util/fnv1a.hpp"

namespace lagrange::controller {

namespace {
using nlohmann::json;

// Bumped when the layout changes: a file of another version is not used.
constexpr int kFormat = 1;
// A report is a few kB; anything far larger is not one.
constexpr std::uintmax_t kMaxGainsBytes = 1u << 20;

std::string fingerprint(const std::string& scenario_yaml) { return util::fnv1a64Hex(scenario_yaml); }

// JSON has no infinity or NaN (nlohmann would write null); a margin or a
// spectral radius can be either.
json number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return x;
}
double numberFrom(const json& j) {
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
  }
  return j.get<double>();  // any other string: nlohmann's type_error
}

json conditionJson(const model::ConditionReport& c) {
  const std::string label = model::paperLabel(c.name);
  return {{"name", c.name},
          {"paper_label", label.empty() ? json(nullptr) : json(label)},
          {"expression", c.expression},
          {"lhs", number(c.lhs)},
          {"rhs", number(c.rhs)},
          {"holds", c.holds}};
}
model::ConditionReport conditionFrom(const json& j) {
  model::ConditionReport c;
  c.name = j.at("name").get<std::string>();
  c.expression = j.at("expression").get<std::string>();
  c.lhs = numberFrom(j.at("lhs"));
  c.rhs = numberFrom(j.at("rhs"));
  c.holds = j.at("holds").get<bool>();
  return c;
}
json conditionsJson(const std::vector<model::ConditionReport>& list) {
  json out = json::array();
  for (const auto& c : list) out.push_back(conditionJson(c));
  return out;
}
std::vector<model::ConditionReport> conditionsFrom(const json& j) {
  std::vector<model::ConditionReport> out;
  for (const json& c : j) out.push_back(conditionFrom(c));
  return out;
}

json sampledJson(const SampledDataCheck& s) {
  return {{"rate", number(s.rate)},
          {"spectral_radius", number(s.spectral_radius)},
          {"worst_time", number(s.worst_time)},
          {"sampled_decay", number(s.sampled_decay)},
          {"continuous_decay", number(s.continuous_decay)},
          {"fastest_mode", number(s.fastest_mode)},
          {"verdict", s.verdict},
          {"why", s.why},
          {"sufficient_rate", s.sufficient_rate ? number(*s.sufficient_rate) : json(nullptr)},
          {"one_period_delay", s.one_period_delay}};
}
SampledDataCheck sampledFrom(const json& j) {
  SampledDataCheck s;
  s.rate = numberFrom(j.at("rate"));
  s.spectral_radius = numberFrom(j.at("spectral_radius"));
  s.worst_time = numberFrom(j.at("worst_time"));
  s.sampled_decay = numberFrom(j.at("sampled_decay"));
  s.continuous_decay = numberFrom(j.at("continuous_decay"));
  s.fastest_mode = numberFrom(j.at("fastest_mode"));
  s.verdict = j.at("verdict").get<std::string>();
  s.why = j.at("why").get<std::string>();
  if (!j.at("sufficient_rate").is_null()) s.sufficient_rate = numberFrom(j.at("sufficient_rate"));
  s.one_period_delay = j.at("one_period_delay").get<bool>();
  return s;
}

json optionalNumber(const std::optional<double>& v) { return v ? number(*v) : json(nullptr); }
std::optional<double> optionalFrom(const json& j) {
  return j.is_null() ? std::nullopt : std::optional<double>(numberFrom(j));
}

}  // namespace

nlohmann::json sampledSimulationJson(const SampledSimulation& c) {
  json starts = json::array();
  for (const SampledSimulation::Start& s : c.starts)
    starts.push_back({{"what", s.what},
                      {"sampled_status", s.sampled_status},
                      {"fine_status", s.fine_status},
                      {"sampled_time", optionalNumber(s.sampled_time)},
                      {"fine_time", optionalNumber(s.fine_time)},
                      {"sampled_error", number(s.sampled_error)},
                      {"fine_error", number(s.fine_error)},
                      {"verdict", s.verdict},
                      {"initial_error", number(s.initial_error)}});
  return {{"rate", number(c.rate)},
          {"fine_rate", number(c.fine_rate)},
          {"confirmed_at", optionalNumber(c.confirmed_at)},
          {"duration", number(c.duration)},
          {"tolerance", number(c.tolerance)},
          {"one_period_delay", c.one_period_delay},
          {"starts", starts},
          {"verdict", c.verdict},
          {"why", c.why},
          {"wall_time", number(c.wall_time)}};
}
namespace {

SampledSimulation simulationFrom(const json& j) {
  SampledSimulation c;
  c.rate = numberFrom(j.at("rate"));
  c.fine_rate = numberFrom(j.at("fine_rate"));
  c.confirmed_at = optionalFrom(j.at("confirmed_at"));
  c.duration = numberFrom(j.at("duration"));
  c.tolerance = numberFrom(j.at("tolerance"));
  c.one_period_delay = j.at("one_period_delay").get<bool>();
  for (const json& s : j.at("starts"))
    c.starts.push_back({s.at("what").get<std::string>(), s.at("sampled_status").get<std::string>(),
                        s.at("fine_status").get<std::string>(), optionalFrom(s.at("sampled_time")),
                        optionalFrom(s.at("fine_time")), numberFrom(s.at("sampled_error")),
                        numberFrom(s.at("fine_error")), s.at("verdict").get<std::string>(),
                        numberFrom(s.at("initial_error"))});
  c.verdict = j.at("verdict").get<std::string>();
  c.why = j.at("why").get<std::string>();
  c.wall_time = numberFrom(j.at("wall_time"));
  return c;
}

// Every field of GainReport (controller/gain_report.hpp): a field added
// there is added here, or the processes lose it.
json reportJson(const GainReport& r) {
  json j = {{"kc", number(r.kc)},
            {"kc_proven", r.kc_proven},
            {"kc_found", number(r.kc_found)},
            {"kdelta", number(r.kdelta)},
            {"kdelta_exact", r.kdelta_exact},
            {"condition", conditionJson(r.condition)},
            {"chain", conditionsJson(r.chain)},
            {"proposition", conditionsJson(r.proposition)},
            {"eta", nullptr},
            {"warnings", r.warnings},
            {"sampled", sampledJson(r.sampled)},
            {"simulated", r.simulated ? sampledSimulationJson(*r.simulated) : json(nullptr)},
            {"unchecked", r.unchecked ? json(*r.unchecked) : json(nullptr)}};
  if (r.eta)
    j["eta"] = {{"eta1", number(r.eta->eta1)}, {"eta2", number(r.eta->eta2)}, {"eta3", number(r.eta->eta3)}};
  return j;
}
GainReport reportFrom(const json& j) {
  GainReport r;
  r.kc = numberFrom(j.at("kc"));
  r.kc_proven = j.at("kc_proven").get<bool>();
  r.kc_found = numberFrom(j.at("kc_found"));
  r.kdelta = numberFrom(j.at("kdelta"));
  r.kdelta_exact = j.at("kdelta_exact").get<bool>();
  r.condition = conditionFrom(j.at("condition"));
  r.chain = conditionsFrom(j.at("chain"));
  r.proposition = conditionsFrom(j.at("proposition"));
  if (const json& eta = j.at("eta"); !eta.is_null())
    r.eta = model::EtaEstimate{numberFrom(eta.at("eta1")), numberFrom(eta.at("eta2")),
                               numberFrom(eta.at("eta3"))};
  r.warnings = j.at("warnings").get<std::vector<std::string>>();
  r.sampled = sampledFrom(j.at("sampled"));
  if (const json& simulated = j.at("simulated"); !simulated.is_null())
    r.simulated = simulationFrom(simulated);
  if (const json& why = j.at("unchecked"); !why.is_null()) r.unchecked = why.get<std::string>();
  return r;
}
}  // namespace

std::string gainReportJson(const GainReport& report, const std::string& scenario_yaml) {
  const json j = {
      {"what", "the gain check lagrange run made before starting this run (summary.json's gains)"},
      {"format", kFormat},
      {"scenario_fnv1a64", fingerprint(scenario_yaml)},
      {"report", reportJson(report)}};
  return j.dump(2) + "\n";
}

HandedGainReport gainReportFromJson(const std::string& json_text, const std::string& scenario_yaml) {
  HandedGainReport out;
  try {
    const json j = json::parse(json_text);
    if (j.at("format").get<int>() != kFormat) {
      out.why_not = "it has format " + j.at("format").dump() + ", expected " + std::to_string(kFormat);
    } else if (j.at("scenario_fnv1a64").get<std::string>() != fingerprint(scenario_yaml)) {
      out.why_not = "it was computed for another scenario";
    } else {
      out.report = reportFrom(j.at("report"));
    }
  } catch (const json::exception& e) {
    out.why_not = std::string("it is not a gain report (") + e.what() + ")";
  }
  return out;
}

ProcessGainReport processGainReport(const config::Scenario& scenario, const std::string& path) {
  ProcessGainReport out;
  if (!path.empty()) {
    const config::FileText file = config::readRegularFile(path, kMaxGainsBytes, "the launcher's gains.json");
    HandedGainReport handed;
    if (file.error.empty()) handed = gainReportFromJson(file.text, config::toYaml(scenario));
    if (handed.report) {
      out.report = std::move(*handed.report);
      if (!out.report.sampled.verdict.empty()) out.sampled = out.report.sampled;
      out.report.sampled = SampledDataCheck{};  // as checkGains(s, false) leaves it
      return out;
    }
    out.note = "--gains " + path + " not used (" + (file.error.empty() ? handed.why_not : file.error) +
               "): checking the gains here";
  }
  out.report = checkGains(scenario, false);
  return out;
}

}  // namespace lagrange::controller
