#include "tools/keys/key_listing.hpp"

#include <sstream>

#include "config/key_reference.hpp"
#include "config/key_table.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

namespace {

bool inSection(const std::string& key, const std::string& section) {
  if (key.compare(0, section.size(), section) != 0) return false;
  return key.size() == section.size() || key[section.size()] == '.' || key[section.size()] == '[';
}

// The columns UTF-8 text takes on a terminal: one per character, not per
// byte ("≥", "²" and "á" are two or three bytes each).
int columns(const std::string& text) {
  int n = 0;
  for (const char c : text) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

// Words of `text` on lines of at most `width` columns (a longer word has its own line).
std::string wrapped(const std::string& text, const std::string& indent, int width) {
  std::istringstream words(text);
  std::string out, line, word;
  while (words >> word) {
    if (!line.empty() && columns(indent) + columns(line) + 1 + columns(word) > width) {
      out += indent + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty()) out += indent + line + "\n";
  return out;
}

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
