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

}  // namespace lagrange::tools
