#include "logs/log_reader.hpp"

#include "config/scenario.hpp"
#include "lagrange/scenario_t.hpp"
#include "transport/channels.hpp"

namespace lagrange::logs {

std::optional<std::string> scenarioYaml(const lcm::LogEvent& ev) {
  lagrange::scenario_t m;
  if (!decodeEvent(ev, m)) return std::nullopt;
  return m.yaml;
}

EventBounds boundsOfLog(const std::string& path) {
  LogEventReader reader(path);
  reader.readOnly(transport::kScenario);  // every other event passed over unread
  for (;;) {
    const lcm::LogEvent* ev = reader.next();
    // The first SCENARIO was over its bound, and skipped: no scenario is that large.
    if (!reader.scan().first_oversized.empty()) {
      const OversizedEvent& e = reader.scan().first_oversized.front();
      throw LogError(
          path + ": the SCENARIO at byte " + std::to_string(e.offset) + " holds " + std::to_string(e.bytes) +
          " bytes; a scenario is at most " + std::to_string(e.bound) +
          " (a scenario file of at most 1 MiB resolved with its URDF inline); expected the log of a "
          "lagrange run");
    }
    if (ev == nullptr) return EventBounds::projectLimits("no SCENARIO in the log");
    const std::optional<std::string> yaml = scenarioYaml(*ev);
    if (!yaml) continue;  // not a scenario_t: the next SCENARIO may be (as replay reads them)
    try {
      const config::Scenario s = config::parseLoggedScenario(*yaml, path + ":SCENARIO");
      const MessageShape shape = shapeOf(s.dof(), s.actuator.order, s.torqueStepsPerTick());
      return EventBounds(
          shape,
          "the log's scenario (" + shape.describe() + ", ticks 0 to " + std::to_string(s.lastTick()) + ")",
          s.lastTick());
    } catch (const std::exception&) {
      return EventBounds::projectLimits("the log's SCENARIO is not a valid scenario");
    }
  }
}

LogScan readLog(const std::string& path, const std::function<void(const lcm::LogEvent&)>& on_event) {
  EventBounds bounds = boundsOfLog(path);
  LogEventReader reader(path);
  reader.limitEvents(std::move(bounds));
  while (const lcm::LogEvent* ev = reader.next()) on_event(*ev);
  return reader.scan();
}

}  // namespace lagrange::logs
