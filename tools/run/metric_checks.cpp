#include "tools/run/metric_checks.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "config/scenario.hpp"
#include "tools/run/run_outcome.hpp"

namespace lagrange::tools {

namespace {

// Short names for the numbers CI jobs ask about most.
const std::map<std::string, std::string>& aliases() {
  static const std::map<std::string, std::string> names = {
      {"final_error", "tracking.final_error"},
      {"max_error", "tracking.max_error"},
      {"convergence_time", "tracking.convergence_time"},
      {"rms_last_second", "tracking.rms_last_second"},
      {"max_torque", "torque.max_abs"},
  };
  return names;
}

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

const nlohmann::json* find(const nlohmann::json& j, const std::string& dotted) {
  const nlohmann::json* at = &j;
  size_t start = 0;
  while (start <= dotted.size()) {
    const size_t dot = dotted.find('.', start);
    const std::string part = dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!at->is_object() || !at->contains(part)) return nullptr;
    at = &(*at)[part];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return at;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

bool compare(double value, const std::string& op, double threshold) {
  if (op == "<") return value < threshold;
  if (op == "<=") return value <= threshold;
  if (op == ">") return value > threshold;
  return value >= threshold;
}

std::string xmlEscaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        // XML 1.0 allows no other control characters
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\n' || c == '\t') out += c;
    }
  }
  return out;
}

}  // namespace

MetricCheck parseMetricCheck(const std::string& raw) {
  const std::string text = trimmed(raw);
  MetricCheck c;
  c.text = text;
  if (text == "met" || text == "no_warnings") {
    c.key = text;
    return c;
  }
  const size_t at = text.find_first_of("<>");
  const auto grammar = [&](std::string what) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(text, ec))
      what +=
          " (it is a file: was the scenario taken for --check's value? write --check=LIST, or --check after "
          "it)";
    return config::ConfigError(
        "--check '" + raw + "': " + what +
        "; expected met, no_warnings, or KEY OP NUMBER with OP one of < <= > >= and KEY a number "
        "of summary.json (e.g. tracking.final_error) or one of final_error, "
        "max_error, convergence_time, rms_last_second, max_torque: "
        "--check 'met,final_error<1e-4,max_torque<=300'");
  };
  if (at == std::string::npos || at == 0) throw grammar(text.empty() ? "empty" : "no comparison");
  c.op = text.substr(at, text.size() > at + 1 && text[at + 1] == '=' ? 2 : 1);
  const std::string key = trimmed(text.substr(0, at)), value = trimmed(text.substr(at + c.op.size()));
  c.key = aliases().count(key) ? aliases().at(key) : key;
  char* end = nullptr;
  c.threshold = std::strtod(value.c_str(), &end);
  if (value.empty() || end == nullptr || *end != '\0' || !std::isfinite(c.threshold))
    throw grammar("'" + value + "' is not a finite number");
  if (c.key.empty() || c.key.find_first_of(" <>=") != std::string::npos) throw grammar("no key");
  if (c.key == "met" || c.key == "no_warnings") throw grammar(c.key + " takes no comparison");
  return c;
}

std::vector<CheckResult> evaluateChecks(const std::vector<MetricCheck>& checks,
                                        const nlohmann::json& summary) {
  std::vector<CheckResult> out;
  const bool completed = summary.is_object() && summary.value("status", "") == "completed";
  for (const MetricCheck& c : checks) {
    CheckResult r{c, false, ""};
    if (!summary.is_object()) {
      r.message = c.text + ": summary.json could not be read; expected the logger's summary of this run";
    } else if (!completed) {
      r.message = c.text + ": the run did not complete (status " +
                  summary.value("status", std::string("unknown")) + ")";
    } else if (c.key == "met") {
      const std::vector<std::string> missed = missedMetrics(summary);
      r.passed = missed.empty();
      r.message = r.passed ? "the stated metric is met" : missed.front();
      for (size_t i = 1; i < missed.size(); ++i) r.message += "; " + missed[i];
    } else if (c.key == "no_warnings") {
      const nlohmann::json* warnings = find(summary, "verdict.warnings");
      r.passed = warnings != nullptr && warnings->is_array() && warnings->empty();
      r.message = warnings == nullptr || !warnings->is_array()
                      ? "no_warnings: summary.json has no verdict.warnings"
                  : r.passed ? "the run's verdict has no warnings"
                             : "the run's verdict has " + std::to_string(warnings->size()) +
                                   " warning(s): " + (*warnings)[0].value("text", std::string());
    } else if (const nlohmann::json* v = find(summary, c.key); v == nullptr) {
      r.message = c.text + ": summary.json has no " + c.key;
    } else if (v->is_null()) {
      r.message = c.text + ": " + c.key + " is null (" +
                  (c.key == "tracking.convergence_time" ? "never converged" : "none") + ")";
    } else if (!v->is_number()) {
      r.message = c.text + ": " + c.key + " is not a number in summary.json";
    } else {
      const double value = v->get<double>();
      r.passed = compare(value, c.op, c.threshold);
      r.message = c.text + ": " + c.key + " = " + number(value) + (r.passed ? " " : ", not ") + c.op + " " +
                  number(c.threshold);
    }
    out.push_back(r);
  }
  return out;
}

std::string junitXml(const std::string& scenario_name, const std::vector<CheckResult>& results,
                     double wall_time) {
  int failures = 0;
  for (const CheckResult& r : results) failures += r.passed ? 0 : 1;
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += "<testsuites tests=\"" + std::to_string(results.size()) + "\" failures=\"" +
         std::to_string(failures) + "\">\n";
  xml += "  <testsuite name=\"lagrange run " + xmlEscaped(scenario_name) + "\" tests=\"" +
         std::to_string(results.size()) + "\" failures=\"" + std::to_string(failures) +
         "\" errors=\"0\" time=\"" + number(wall_time) + "\">\n";
  for (const CheckResult& r : results) {
    xml += "    <testcase classname=\"" + xmlEscaped(scenario_name) + "\" name=\"" +
           xmlEscaped(r.check.text) + "\">";
    if (r.passed)
      xml += "<system-out>" + xmlEscaped(r.message) + "</system-out>";
    else
      xml += "\n      <failure message=\"" + xmlEscaped(r.message) + "\"/>\n    ";
    xml += "</testcase>\n";
  }
  xml += "  </testsuite>\n</testsuites>\n";
  return xml;
}

}  // namespace lagrange::tools
