#include "tools/replay/log_damage.hpp"

#include <map>

#include "transport/channels.hpp"

namespace lagrange::tools::replay_log {

std::string tickRange(int64_t from, int64_t to) {
  return from == to ? "tick " + std::to_string(from)
                    : "ticks " + std::to_string(from) + " to " + std::to_string(to);
}

std::string channelOneByteFrom(const std::string& name) {
  for (const transport::ChannelInfo& info : transport::kChannelTable) {
    const std::string channel = info.name;
    if (!info.per_tick || channel.size() != name.size()) continue;
    int differing = 0;
    for (size_t i = 0; i < name.size(); ++i) differing += name[i] != channel[i];
    if (differing == 1) return channel;
  }
  return "";
}

std::string whatMayHaveHeld(const LogDamage& damage, const std::string& channel, int64_t from, int64_t to,
                            long long lower, long long upper) {
  std::vector<std::string> clauses;
  for (const DamagedEvent& e : damage.events) {
    if (e.channel != channel || clauses.size() == 3) continue;
    if (e.tick && *e.tick >= from && *e.tick <= to)
      clauses.push_back("the copy of " + channel + " tick " + std::to_string(*e.tick) +
                        " it holds is corrupt: the event at byte " + std::to_string(e.offset) + " " + e.why);
    else if (e.offset > lower && e.offset < upper)  // its tick, if any, may be the damaged part
      clauses.push_back("the event at byte " + std::to_string(e.offset) +
                        (e.tick ? ", which names tick " + std::to_string(*e.tick) + "," : "") + " " + e.why +
                        " and may have held " + tickRange(from, to));
  }
  for (const SkippedStretch& s : damage.skipped)
    if (clauses.size() < 3 && s.offset + s.bytes > lower && s.offset < upper)
      clauses.push_back(std::to_string(s.bytes) + " corrupt bytes skipped at byte " +
                        std::to_string(s.offset) + " may have held " + tickRange(from, to));
  std::string out;
  for (const std::string& c : clauses) out += (out.empty() ? "" : "; ") + c;
  return out;
}

std::string describe(const LogDamage& damage) {
  std::map<std::string, long long> per_channel;
  for (const DamagedEvent& e : damage.events) ++per_channel[e.channel];
  std::string channels;
  for (const auto& [channel, n] : per_channel)
    channels += (channels.empty() ? "" : ", ") + std::to_string(n) + " on " + channel;
  const DamagedEvent& first = damage.events.front();
  return std::to_string(damage.events.size()) + (damage.events.size() == 1 ? " event" : " events") +
         " of this project's channels cannot be used (" + channels + "; the first, at byte " +
         std::to_string(first.offset) + ", " + first.why +
         "): corrupted on the way (the intact copy is re-sent in lockstep) or in the file, or another "
         "version's types. Skipped";
}

}  // namespace lagrange::tools::replay_log
