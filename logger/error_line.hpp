#pragma once
/// @file
/// The logger's last word to the launcher when it stops on an error: one
/// line "error: WHAT" on its progress pipe (--progress-fd). The launcher
/// prints it; the logger's own log may be on the disk that just filled up.

#include <unistd.h>

#include <string>

namespace lagrange::logger {

inline constexpr const char* kLoggerErrorPrefix = "error: ";
/// A line for the launcher to print as it comes ("notice: WHAT"): a slow
/// answer while it lasts (logger/answer_times.hpp).
inline constexpr const char* kLoggerNoticePrefix = "notice: ";

/// One line PREFIX + WHAT on the pipe; best effort, like the progress lines:
/// never blocks, never throws.
inline void sendPrefixedLine(int fd, const char* prefix, const std::string& what) {
  if (fd < 0) return;
  std::string line = prefix + what;
  for (char& c : line)
    if (c == '\n') c = ' ';
  line += '\n';
  [[maybe_unused]] const ssize_t written = write(fd, line.data(), line.size());
}
inline void sendErrorLine(int fd, const std::string& what) { sendPrefixedLine(fd, kLoggerErrorPrefix, what); }
inline void sendNoticeLine(int fd, const std::string& what) {
  sendPrefixedLine(fd, kLoggerNoticePrefix, what);
}

}  // namespace lagrange::logger
