#include "config/key_ranges.hpp"

#include <cstdio>
#include <regex>

#include "config/key_table.hpp"

namespace lagrange::config {

std::string shortNumber(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent = exponent.substr(1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::string rangeText(const KeyRange& r) {
  const std::string unit = r.unit.empty() ? "" : " " + r.unit;
  if (r.min_exclusive) return "> " + shortNumber(r.min) + " and at most " + shortNumber(r.max) + unit;
  return "from " + shortNumber(r.min) + " to " + shortNumber(r.max) + unit;
}

std::string rangeKey(const std::string& key_path) {
  static const std::regex index(R"(\[[0-9]+\])");
  static const std::regex channel(R"(^faults\.channels\.[^.]+\.)");
  static const std::regex receiver(R"(^faults\.receivers\.[^.]+\.)");
  std::string key = std::regex_replace(key_path, index, "[i]");
  key = std::regex_replace(key, channel, "faults.channels.NAME.");
  key = std::regex_replace(key, receiver, "faults.receivers.PROCESS.");
  if (key == "actuator.initial_state[i].row") key = "actuator.initial_state";
  return key;
}

const std::map<std::string, KeyRange>& keyRanges() {
  static const std::map<std::string, KeyRange> ranges = [] {
    std::map<std::string, KeyRange> by_key;
    for (const KeyInfo& k : keyTable())
      if (k.range) by_key.emplace(k.key, *k.range);
    return by_key;
  }();
  return ranges;
}

const KeyRange* rangeOf(const std::string& key_path) {
  const auto& table = keyRanges();
  const auto it = table.find(rangeKey(key_path));
  return it == table.end() ? nullptr : &it->second;
}

}  // namespace lagrange::config
