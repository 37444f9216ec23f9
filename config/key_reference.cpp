/// @file
/// docs/configuration.md's table of keys, rendered from the key table
/// (config/key_reference.hpp).
#include "config/key_reference.hpp"

#include <map>
#include <utility>
#include <vector>

namespace lagrange::config {

namespace {

// The last part of a key, as its row's text names it ("robot.links[i].mass" -> "mass").
std::string shortKey(const std::string& key) { return key.substr(key.find_last_of('.') + 1); }

std::string rangeWithWhy(const KeyRange& r) {
  return rangeText(r) + (r.why.empty() ? "" : " (" + r.why + ")");
}

}  // namespace

// Keys of one range together, in the order of their names.
std::string rangeSentence(const KeyInfo& row) {
  std::vector<const KeyInfo*> ranged;
  if (row.range) ranged.push_back(&row);
  std::map<std::string, const KeyInfo*> described;  // by short name
  for (const KeyInfo& k : keyTable())
    if (k.described_in == row.key && k.range) described[shortKey(k.key)] = &k;
  for (const auto& entry : described) ranged.push_back(entry.second);
  if (ranged.empty()) return "";
  if (ranged.size() == 1 && ranged[0] == &row) return " Range: " + rangeWithWhy(*row.range) + ".";
  std::vector<std::pair<std::string, std::string>> groups;  // range text, "`a`, `b`"
  for (const KeyInfo* k : ranged) {
    const std::string text = rangeWithWhy(*k->range);
    const std::string name = "`" + shortKey(k->key) + "`";
    auto group = groups.begin();
    while (group != groups.end() && group->first != text) ++group;
    if (group == groups.end())
      groups.push_back({text, name});
    else
      group->second += ", " + name;
  }
  std::string sentence = " Ranges: ";
  for (size_t i = 0; i < groups.size(); ++i)
    sentence += (i == 0 ? "" : "; ") + groups[i].second + " " + groups[i].first;
  return sentence + ".";
}

std::string keyReferenceMarkdown() {
  std::string out = "| key | type | default | meaning |\n| --- | --- | --- | --- |\n";
  for (const KeyInfo& k : keyTable()) {
    if (!k.described_in.empty()) continue;
    out += "| `" + k.key + "` | " + k.type + " | " + k.default_text + " | " + k.meaning + rangeSentence(k) +
           " |\n";
  }
  return out;
}

}  // namespace lagrange::config
