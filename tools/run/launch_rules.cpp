#include "tools/run/launch_rules.hpp"

#include <algorithm>

namespace lagrange::tools {

bool runsHere(const RunOptions& opt, const std::string& process) {
  return opt.processes.empty() ||
         std::find(opt.processes.begin(), opt.processes.end(), process) != opt.processes.end();
}

// A run spread over hosts: each launcher starts its share, on a URL they all use.
std::string checkProcesses(const RunOptions& opt) {
  for (size_t i = 0; i < opt.processes.size(); ++i) {
    const std::string& p = opt.processes[i];
    if (std::find(kProcesses.begin(), kProcesses.end(), p) == kProcesses.end())
      return "--processes: unknown process '" + p + "'; expected some of logger, controller, actuator, plant";
    if (std::find(opt.processes.begin(), opt.processes.begin() + static_cast<long>(i), p) !=
        opt.processes.begin() + static_cast<long>(i))
      return "--processes: '" + p + "' given twice; expected each process once";
  }
  if (opt.processes.empty() || opt.processes.size() == kProcesses.size()) return "";
  if (opt.private_netns)
    return "--processes starts part of a run here and the rest runs elsewhere, which a private network "
           "namespace would cut off; add --no-netns";
  if (opt.lcm_url.empty())
    return "--processes: every host must use the same LCM URL; give it with --lcm-url (TTL 1 or more to "
           "cross hosts, e.g. udpm://239.255.76.67:7667?ttl=1)";
  if (opt.key_file.empty())
    return "--processes: every host must sign with the same secret key; make one with `lagrange keygen "
           "FILE`, copy it to each host (mode 600) and give it with --key-file FILE";
  return "";
}

int64_t sharedRunId(const std::string& lcm_url, const std::string& resolved_text) {
  const std::string text = lcm_url + "\n" + resolved_text;
  uint64_t h = 1469598103934665603ULL;
  for (const unsigned char ch : text) h = (h ^ ch) * 1099511628211ULL;
  return static_cast<int64_t>(h >> 1) | 1;
}

nlohmann::json supervisionRecord(const config::SupervisionConfig& policy) {
  return {{"restart", policy.restart},
          {"restarts", nlohmann::json::object()},
          {"deaths", nlohmann::json::array()}};
}

bool mayRestart(const config::SupervisionConfig& policy, nlohmann::json& supervision,
                const std::string& process, const std::string& how_it_died) {
  const int done = supervision["restarts"].value(process, 0);
  const bool restart = policy.restarts(process) && done < policy.max_restarts;
  supervision["deaths"].push_back({{"process", process}, {"how", how_it_died}, {"restarted", restart}});
  if (restart) supervision["restarts"][process] = done + 1;
  return restart;
}

std::string plantEndedEarly(const nlohmann::json& summary, long long last_tick) {
  if (!summary.is_object() || summary.value("status", "") == "completed") return "";
  const nlohmann::json plant =
      summary.value("processes", nlohmann::json::object()).value("plant", nlohmann::json());
  const bool finished = plant.is_object() && plant.value("state", "") == "finished";
  const long long said = plant.is_object() ? plant.value("last_tick", -1LL) : -1;
  long long missing = 0;
  if (const auto log = summary.find("log"); log != summary.end() && log->is_object())
    if (const auto gaps = log->find("missing_ticks"); gaps != log->end() && gaps->is_object())
      missing = gaps->value("PLANT_TRUTH", 0LL);
  if (finished && said < last_tick)
    return "said \"finished\" at tick " + std::to_string(said) + ", before the run's last tick " +
           std::to_string(last_tick) + ", and exited with code 0";
  if (finished) {
    // At the last tick: in lockstep every sample reaches the logger (the
    // plant re-sends until it confirms), so a gap is the plant's; in
    // realtime a last sample lost on the way is no plant's fault (the
    // verdict weighs what the log lacks).
    if (summary.value("mode", "") == "lockstep" && missing > 0)
      return "said \"finished\" at the run's last tick, but the log lacks PLANT_TRUTH for " +
             std::to_string(missing) +
             " of the run's ticks (skipped, or never confirmed by the logger), and exited with code 0";
    return "";
  }
  return "exited with code 0 before the run's last tick (the others waited for its \"finished\" STATUS)";
}

}  // namespace lagrange::tools
