#include "tools/run/run_outcome.hpp"

#include <cstdarg>
#include <cstdio>
#include <sstream>

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
}  // namespace

std::string resultText(const nlohmann::json& j) {
  const auto& t = j.at("tracking");
  std::string out = format("\nscenario %s: %s\n", j.at("scenario").get<std::string>().c_str(),
                           j.at("status").get<std::string>().c_str());
  out += format("  final tracking error  %.3e rad (tolerance %.1e)\n", t.at("final_error").get<double>(),
                t.at("tolerance").get<double>());
  if (t.at("convergence_time").is_null())
    out += "  convergence time      never (the error did not stay below the tolerance)\n";
  else
    out += format("  convergence time      %.3f s (deadline %.3f s: %s)\n",
                  t.at("convergence_time").get<double>(), t.at("convergence_deadline").get<double>(),
                  t.at("met").get<bool>() ? "met" : "MISSED");
  out += format("  max |torque|          %.3f N m\n", j.at("torque").at("max_abs").get<double>());
  // A controller without a known stability condition has no verdict to print.
  const auto& gains = j.at("gains");
  if (gains.value("checked", true))
    out += format("  gain condition        %s (margin %.4g)\n",
                  gains.at("condition_holds").get<bool>() ? "holds" : "VIOLATED",
                  gains.at("margin").get<double>());
  else
    out += format("  gain condition        not checked (%s)\n", gains.value("why", "").c_str());
  const auto& timing = j.at("timing");
  out += format("  sim %.2f s in %.2f s wall (%.1fx real time)\n", timing.at("sim_time").get<double>(),
                timing.at("wall_time").get<double>(), timing.at("realtime_factor").get<double>());
  return out;
}

std::vector<std::string> missedMetrics(const nlohmann::json& j) {
  const auto& t = j.at("tracking");
  if (t.at("met").get<bool>()) return {};
  const double deadline = t.at("convergence_deadline").get<double>();
  std::vector<std::string> missed;
  std::ostringstream line;
  line << "metric MISSED: ||q~|| below " << t.at("tolerance").get<double>() << " rad by t = " << deadline
       << " s and staying there: converged " << when(t.at("convergence_time")) << ", final error "
       << t.at("final_error").get<double>() << " rad";
  missed.push_back(line.str());
  if (t.contains("chain"))
    for (const auto& c : t.at("chain"))
      if (c.at("convergence_time").is_null() || c.at("convergence_time").get<double>() > deadline) {
        std::ostringstream stage;
        stage << "metric MISSED: ||xit_" << c.at("stage").get<int>() << "|| below "
              << c.at("tolerance").get<double>() << " by t = " << deadline << " s: converged "
              << when(c.at("convergence_time")) << ", final error " << c.at("final_error").get<double>();
        missed.push_back(stage.str());
      }
  return missed;
}

}  // namespace lagrange::tools
