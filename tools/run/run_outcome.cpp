#include "tools/run/run_outcome.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <sstream>

#include "logger/verdict.hpp"
#include "util/terminal_text.hpp"

namespace lagrange::tools {

namespace {
// printf into a string (the block's columns are printf's).
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  va_list args, again;
  va_start(args, fmt);
  va_copy(again, args);
  const int length = std::vsnprintf(nullptr, 0, fmt, args);  // a scenario's name has no bound
  va_end(args);
  std::string text(length > 0 ? static_cast<size_t>(length) : 0, '\0');
  std::vsnprintf(text.data(), text.size() + 1, fmt, again);
  va_end(again);
  return text;
}

std::string when(const nlohmann::json& convergence_time) {
  return convergence_time.is_null() ? std::string("never")
                                    : std::to_string(convergence_time.get<double>()) + " s";
}

// The verdict summary.json carries (logger/verdict.hpp decides it); a
// summary written before verdicts existed gets one decided the same way.
nlohmann::json verdictOf(const nlohmann::json& j) {
  return j.contains("verdict") && j.at("verdict").is_object() ? j.at("verdict") : logger::runVerdict(j);
}

std::string numberOr(const nlohmann::json& v, const char* fmt, const char* otherwise) {
  return v.is_number() ? format(fmt, v.get<double>()) : std::string(otherwise);
}

// The gain-condition line: the continuous-time condition beside the
// linearised check of the loop sampled at the run's rate -- two different
// claims, never one standing for the other.
std::string gainLine(const nlohmann::json& gains) {
  if (!gains.value("checked", true))
    return format("  gain condition        not checked (%s)\n", gains.value("why", "").c_str());
  // The condition named is the one the verdict and the margin are of: with
  // several (a chain's), the violated one with the smallest margin, or the
  // smallest margin's when all hold -- never eq. (12) beside another's failure.
  const char* name_key = gains.contains("binding_condition") ? "binding_condition" : "condition";
  const auto conditions = gains.find("conditions");
  const std::size_t count = conditions != gains.end() && conditions->is_array() ? conditions->size() : 1;
  std::size_t violated = 0;
  if (count > 1)
    for (const auto& c : *conditions) violated += c.value("holds", true) ? 0 : 1;
  const bool holds = gains.at("condition_holds").get<bool>();
  const std::string name = gains.contains(name_key) ? gains.at(name_key).get<std::string>() + " " : "";
  const std::string of_all = count <= 1
                                 ? ""
                                 : (holds ? format(", the smallest of %zu that hold", count)
                                          : format(", %zu of %zu conditions violated", violated, count));
  std::string line =
      format("  gain condition        %s%s (continuous time; margin %s%s)", name.c_str(),
             holds ? "holds" : "VIOLATED",
             numberOr(gains.at("margin"), "%.4g", "not finite").c_str(),  // infinite: null in JSON
             of_all.c_str());
  if (const auto sd = gains.find("sampled_data"); sd != gains.end() && sd->is_object()) {
    std::string word = sd->value("verdict", std::string("not assessed"));
    std::transform(word.begin(), word.end(), word.begin(), ::toupper);
    line += format("; sampled at %s Hz: %s (linearised check)",
                   numberOr(sd->value("rate", nlohmann::json()), "%g", "?").c_str(), word.c_str());
  }
  return line + "\n";
}

std::string findings(const char* title, const nlohmann::json& list) {
  if (!list.is_array() || list.empty()) return "";
  std::string out = format("  %s\n", title);
  for (const auto& f : list) out += "    - " + util::terminalSafe(f.value("text", std::string())) + "\n";
  return out;
}

}  // namespace

std::string resultText(const nlohmann::json& j) {
  const auto& t = j.at("tracking");
  const nlohmann::json verdict = verdictOf(j);
  std::string out =
      // Names and sentences from files: safe to print (util/terminal_text.hpp).
      format("\nscenario %s: %s -- %s\n", util::terminalSafe(j.at("scenario").get<std::string>()).c_str(),
             util::terminalSafe(j.at("status").get<std::string>()).c_str(),
             util::terminalSafe(verdict.value("headline", std::string())).c_str());
  // A run cut short: its figures cover only what was recorded, and say so.
  const auto span = t.find("span");
  const bool partial = span != t.end() && span->is_object() && !span->value("whole_run", true);
  const std::string until = partial
                                ? " at t = " + numberOr(span->value("to", nlohmann::json()), "%.3f", "?") +
                                      " s, where the record ends"
                                : "";
  out += format("  final tracking error  %s (tolerance %.1e)%s\n",
                numberOr(t.at("final_error"), "%.3e rad", "not measured (no sample)").c_str(),
                t.at("tolerance").get<double>(), until.c_str());
  if (t.contains("max_error") && t.at("max_error").is_number())
    out += format("  max tracking error    %.3e rad%s\n", t.at("max_error").get<double>(),
                  t.contains("max_error_time") && t.at("max_error_time").is_number()
                      ? format(" at t = %.3f s", t.at("max_error_time").get<double>()).c_str()
                      : "");
  if (t.at("convergence_time").is_null())
    out += "  convergence time      never (the error did not stay below the tolerance)\n";
  else
    out += format("  convergence time      %.3f s (deadline %.3f s: %s)\n",
                  t.at("convergence_time").get<double>(), t.at("convergence_deadline").get<double>(),
                  !t.at("met").get<bool>()                           ? "MISSED"
                  : j.at("status").get<std::string>() != "completed" ? "reached, but the run did not complete"
                                                                     : "met");
  const auto& torque = j.at("torque");
  const bool sampled = t.value("samples", 1LL) > 0;  // a run that failed at the start measured nothing
  out += format("  max |torque|          %s%s\n",
                sampled ? numberOr(torque.at("max_abs"), "%.3f N m", "not finite").c_str() : "not measured",
                torque.contains("saturated_fraction") && torque.at("saturated_fraction").is_number()
                    ? format(" (at the saturation limit on %.1f %% of the ticks)",
                             100.0 * torque.at("saturated_fraction").get<double>())
                          .c_str()
                    : "");
  out += gainLine(j.at("gains"));
  const auto& timing = j.at("timing");
  out += format("  sim %.2f s in %.2f s wall (%s real time)\n", timing.at("sim_time").get<double>(),
                timing.at("wall_time").get<double>(),
                numberOr(timing.value("realtime_factor", nlohmann::json()), "%.1fx", "?").c_str());
  out += findings("why not met (most likely first):", verdict.value("reasons", nlohmann::json()));
  out += findings("warnings:", verdict.value("warnings", nlohmann::json()));
  // Every string of summary.json, whatever line it is on (a gain check's why, a verdict word).
  return util::terminalSafeLines(out);
}

std::vector<std::string> missedMetrics(const nlohmann::json& j) {
  const auto& t = j.at("tracking");
  if (t.at("met").get<bool>()) {
    // The metric held on the ticks the log has; the verdict may still say the
    // run was not what it claims (the plant's samples missing from the log).
    const nlohmann::json verdict = verdictOf(j);
    if (verdict.value("met", true)) return {};
    std::vector<std::string> missed{
        "metric met on the ticks the log holds, but the run's verdict is NOT met"};
    for (const auto& reason : verdict.value("reasons", nlohmann::json::array()))
      missed.push_back("why: " + reason.value("text", std::string()));
    return missed;
  }
  const double deadline = t.at("convergence_deadline").get<double>();
  std::vector<std::string> missed;
  const nlohmann::json& own = t.at("convergence_time");
  const bool own_missed = !own.is_number() || own.get<double>() > deadline;  // else a chain stage missed
  std::ostringstream line;
  line << "metric MISSED: ||q~|| below " << t.at("tolerance").get<double>() << " rad by t = " << deadline
       << " s and staying there: converged " << when(t.at("convergence_time")) << ", final error "
       << numberOr(t.at("final_error"), "%g rad", "not measured");
  if (own_missed) missed.push_back(line.str());
  if (t.contains("chain"))
    for (const auto& c : t.at("chain"))
      if (c.at("convergence_time").is_null() || c.at("convergence_time").get<double>() > deadline) {
        std::ostringstream stage;
        stage << "metric MISSED: ||xit_" << c.at("stage").get<int>() << "|| below "
              << c.at("tolerance").get<double>() << " by t = " << deadline << " s: converged "
              << when(c.at("convergence_time")) << ", final error "
              << numberOr(c.at("final_error"), "%g", "not measured");
        missed.push_back(stage.str());
      }
  // Why, as the verdict has it (the same reasons the result block lists).
  for (const auto& reason : verdictOf(j).value("reasons", nlohmann::json::array()))
    missed.push_back("why: " + reason.value("text", std::string()));
  return missed;
}

}  // namespace lagrange::tools
