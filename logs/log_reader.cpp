#include "logs/log_reader.hpp"

#include "lagrange/scenario_t.hpp"

namespace lagrange::logs {

std::optional<std::string> scenarioYaml(const lcm::LogEvent& ev) {
  lagrange::scenario_t m;
  if (!decodeEvent(ev, m)) return std::nullopt;
  return m.yaml;
}

LogScan readLog(const std::string& path, const std::function<void(const lcm::LogEvent&)>& on_event) {
  LogEventReader reader(path);
  while (const lcm::LogEvent* ev = reader.next()) on_event(*ev);
  return reader.scan();
}

}  // namespace lagrange::logs
