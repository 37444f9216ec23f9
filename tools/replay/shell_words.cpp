#include "tools/replay/shell_words.hpp"

#include <cstdio>

namespace lagrange::tools {

std::string shellWord(const std::string& word) {
  bool plain = true;  // only printable ASCII: single quotes keep every byte as it is
  for (const char c : word) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte >= 0x7f) plain = false;
  }
  if (plain) {
    std::string out = "'";
    for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
  }
  std::string out = "$'";
  for (const char c : word) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\'' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte >= 0x7f) {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      out += hex;
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::string shellWords(const std::vector<std::string>& words, std::size_t limit) {
  std::string out;
  for (const std::string& word : words) out += (out.empty() ? "" : " ") + shellWord(word);
  if (out.size() <= limit) return out;
  return out.substr(0, limit) + "... (" + std::to_string(out.size() - limit) + " more characters)";
}

}  // namespace lagrange::tools
