#pragma once
/// @file
/// Text from a file or a program (a scenario's name, a process's last log
/// line, an external program's command) made safe to print on a terminal:
/// control characters -- C0 (ESC among them), DEL and the C1 range encoded in
/// UTF-8 (U+0080..U+009F, which some terminals take as CSI) -- are written
/// as \xNN, so `\e]0;...\a\e[2J` cannot retitle or clear the user's screen.
/// Everything else, UTF-8 letters included, is kept as it is.

#include <cstdio>
#include <string>

namespace lagrange::util {

inline std::string terminalSafe(const std::string& text) {
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
    if (byte < 0x20 || byte == 0x7f) {
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

}  // namespace lagrange::util
