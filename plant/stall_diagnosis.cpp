#include "plant/stall_diagnosis.hpp"

#include <cstdio>
#include <utility>

namespace lagrange::plant {

namespace {

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g s", s);
  return buf;
}

const lagrange::channel_stats_t* find(const std::vector<lagrange::channel_stats_t>& all,
                                      const std::string& channel) {
  for (const auto& c : all)
    if (c.channel == channel) return &c;
  return nullptr;
}

const lagrange::status_t* peer(const StallFacts& f, const std::string& name) {
  const auto it = f.peers.find(name);
  return it == f.peers.end() ? nullptr : &it->second;
}

// "state 'running', answered up to tick 41"
std::string whereIs(const lagrange::status_t& s) {
  return "its last STATUS says '" + s.state + "', up to tick " + std::to_string(s.last_tick);
}

// What the plant itself turned away on a channel: a forger or a program
// without the key shows up here even when nobody else reports.
std::string ownRejections(const StallFacts& f, const std::string& channel) {
  const lagrange::channel_stats_t* c = find(f.own, channel);
  if (c == nullptr) return "";
  const std::string r = describeRejections(*c);
  return r.empty() ? "" : "; the plant itself rejected " + r + " " + channel;
}

// One process's view of its input `channel`: what it accepted and rejected.
std::string inputSeen(const lagrange::status_t& s, const std::string& channel) {
  const lagrange::channel_stats_t* c = find(s.channels, channel);
  if (c == nullptr) return "it reports no counters of " + channel;
  const std::string r = describeRejections(*c);
  // Its STATUS names the last message it refused as invalid, and whose.
  const std::string last =
      s.message.rfind("last refused as invalid: ", 0) == 0 ? " -- " + s.message : std::string();
  return "it accepted " + std::to_string(c->received) + " " + channel +
         (r.empty() ? " and rejected none" : " and rejected " + r) + last;
}

}  // namespace

std::string describeRejections(const lagrange::channel_stats_t& c) {
  if (c.rejected == 0) return "";
  const std::pair<const char*, int64_t> reasons[] = {{"unauthenticated", c.rejected_unauthenticated},
                                                     {"corrupt (checksum)", c.rejected_corrupt},
                                                     {"undecodable", c.rejected_undecodable},
                                                     {"of another run", c.rejected_other_run},
                                                     {"from the wrong publisher", c.rejected_wrong_publisher},
                                                     {"old or repeated", c.rejected_old_or_repeated},
                                                     {"invalid", c.rejected_invalid}};
  std::string parts;
  for (const auto& [what, n] : reasons)
    if (n > 0) parts += (parts.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  return std::to_string(c.rejected) + " (" + parts + ")";
}

std::string describeAnswerStall(const StallFacts& f) {
  const std::string k = std::to_string(f.tick);
  const std::string head =
      "stalled at tick " + k + ": no ACTUATOR_STATE answered it in " + seconds(f.seconds);
  const std::string own = ownRejections(f, "ACTUATOR_STATE") + ownRejections(f, "STATUS");
  const lagrange::status_t* actuator = peer(f, "actuator");
  const lagrange::status_t* controller = peer(f, "controller");
  if (actuator == nullptr)
    return head +
           "; awaited: the actuator, never heard (no STATUS from it: not running, on another LCM URL, "
           "or without the run's key)" +
           own;
  if (actuator->last_tick >= f.tick)
    return head +
           "; awaited: the actuator's ACTUATOR_STATE, lost on the way (the actuator answered up to "
           "tick " +
           std::to_string(actuator->last_tick) + ")" + own;
  std::string why = head + "; awaited: the controller -- no valid CONTROL_COMMAND for tick " + k +
                    " reached the actuator (" + inputSeen(*actuator, "CONTROL_COMMAND") + ")";
  if (controller == nullptr)
    why +=
        "; the controller was never heard (no STATUS from it: not running, on another LCM URL, or "
        "without the run's key)";
  else if (controller->last_tick >= f.tick)
    why += "; the controller answered up to tick " + std::to_string(controller->last_tick);
  else
    why += "; the controller: " + whereIs(*controller) + ", " + inputSeen(*controller, "PLANT_POSITION");
  return why + own;
}

std::string describeLoggerStall(const StallFacts& f, int64_t confirmed) {
  std::string why = "stalled before tick " + std::to_string(f.tick) + ": the logger confirmed ";
  why += confirmed < 0 ? "no tick" : "ticks up to " + std::to_string(confirmed);
  why += " in " + seconds(f.seconds) + " (lockstep.logger_window lets the plant run ahead of it only so far)";
  if (const lagrange::status_t* logger = peer(f, "logger"); logger == nullptr)
    why +=
        "; the logger was never heard (no STATUS from it: not running, on another LCM URL, or without the "
        "run's key)";
  else
    why += "; " + whereIs(*logger) + ", " + inputSeen(*logger, "PLANT_TRUTH");
  return why + ownRejections(f, "STATUS");
}

std::string describeMissingPeers(const StallFacts& f, const std::vector<std::string>& expected) {
  std::string missing;
  for (const std::string& name : expected)
    if (f.peers.count(name) == 0) missing += (missing.empty() ? "" : ", ") + name;
  std::string why = "no STATUS from " + (missing.empty() ? std::string("anyone") : missing) + " in " +
                    seconds(f.seconds) + "; are they running on the same LCM URL, with the run's key?";
  return why + ownRejections(f, "STATUS");
}

}  // namespace lagrange::plant
