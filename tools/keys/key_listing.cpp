#include "tools/keys/key_listing.hpp"

#include "config/key_reference.hpp"
#include "config/key_table.hpp"
#include "util/error.hpp"
#include "util/text_wrap.hpp"

namespace lagrange::tools {

namespace {

bool inSection(const std::string& key, const std::string& section) {
  if (key.compare(0, section.size(), section) != 0) return false;
  return key.size() == section.size() || key[section.size()] == '.' || key[section.size()] == '[';
}

using util::wrapped;

}  // namespace

std::string keyListing(const std::vector<std::string>& sections, int width) {
  for (const std::string& section : sections) {
    bool any = false;
    for (const config::KeyInfo& k : config::keyTable()) any = any || inSection(k.key, section);
    if (any) continue;
    std::string top;
    for (const std::string& key : config::keysUnder("")) top += (top.empty() ? "" : ", ") + key;
    throw BadInput("no scenario key is in '" + section + "'; expected a dotted key or a section: " + top);
  }
  std::string out;
  for (const config::KeyInfo& k : config::keyTable()) {
    if (!k.described_in.empty()) continue;
    bool wanted = sections.empty();
    for (const std::string& section : sections) wanted = wanted || inSection(k.key, section);
    // A key described in this row (robot.links[i].mass in robot.links') selects the row.
    for (const config::KeyInfo& inner : config::keyTable())
      if (inner.described_in == k.key)
        for (const std::string& section : sections) wanted = wanted || inSection(inner.key, section);
    if (!wanted) continue;
    out += k.key + "  (" + k.type + "; default " + k.default_text + ")\n";
    out += wrapped(k.meaning + config::rangeSentence(k), "    ", width);
  }
  return out;
}

}  // namespace lagrange::tools
