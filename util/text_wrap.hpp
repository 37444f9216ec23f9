#pragma once
/// @file
/// Text for a terminal: its width in columns, and words wrapped to a width
/// (`lagrange keys`, every command's and process's --help).

#include <sstream>
#include <string>
#include <vector>

namespace lagrange::util {

/// The columns UTF-8 text takes on a terminal: one per character, not per
/// byte ("≥", "²" and "á" are two or three bytes each).
inline int columns(const std::string& text) {
  int n = 0;
  for (const char c : text) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

/// Words of `text` on lines of at most `width` columns, each starting with
/// `indent` and ending with a newline (a longer word has its own line).
inline std::string wrapped(const std::string& text, const std::string& indent, int width) {
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

/// The end of a program's or a command's --help: `details` wrapped to 80
/// columns, then "Examples:" and one command line each.
inline std::string helpFooter(const std::string& details, const std::vector<std::string>& examples) {
  std::string footer = "\n" + wrapped(details, "", 80) + "\nExamples:\n";
  for (const std::string& example : examples) footer += "  " + example + "\n";
  return footer;
}

}  // namespace lagrange::util
