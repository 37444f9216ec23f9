#pragma once
/// @file
/// Text from a file or a program (a scenario's name, a process's last log
/// line, an external program's command) made safe to print on a terminal:
/// control characters -- C0 (ESC among them), DEL and the C1 range encoded in
/// UTF-8 (U+0080..U+009F, which some terminals take as CSI) -- are written
/// as \xNN, so `\e]0;...\a\e[2J` cannot retitle or clear the user's screen.
/// Everything else, UTF-8 letters included, is kept as it is. Every command
/// prints what came from a file, a log, the network or another program
/// through it: names, warnings, errors (tools/command_error.hpp), a failed
/// process's last lines. Escaping twice changes nothing more (a backslash is
/// printable).

#include <cstdio>
#include <string>

namespace lagrange::util {

/// `keep_lines`: newlines and tabs are kept as they are (a message of
/// several lines, a table); a carriage return, which would let a line
/// overwrite what was printed before it, is still escaped.
inline std::string terminalSafe(const std::string& text, bool keep_lines = false) {
  std::string out;
  out.reserve(text.size());
  const auto hex = [&out](unsigned char byte) {
    char code[5];
    std::snprintf(code, sizeof code, "\\x%02x", byte);
    out += code;
  };
  for (size_t i = 0; i < text.size(); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const auto next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0;
    if (keep_lines && (byte == '\n' || byte == '\t')) {
      out += text[i];
    } else if (byte < 0x20 || byte == 0x7f) {
      hex(byte);
    } else if (byte == 0xc2 && next >= 0x80 && next <= 0x9f) {  // a C1 control in UTF-8
      hex(byte);
      hex(next);
      ++i;
    } else {
      out += text[i];
    }
  }
  return out;
}

/// terminalSafe keeping lines: for messages and blocks of several lines.
inline std::string terminalSafeLines(const std::string& text) { return terminalSafe(text, true); }

}  // namespace lagrange::util
