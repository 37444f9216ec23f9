#pragma once
/// @file
/// The launcher's end of the logger's progress pipe: "sim_time
/// tracking_error" lines for the progress bar, and the logger's last word
/// when it stops on an error (logger/error_line.hpp) -- its own log may be on
/// the disk that just filled up.

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lagrange::tools {

class ProgressReader {
 public:
  explicit ProgressReader(int fd) : fd_(fd) {}
  /// Waits up to timeout_ms for data; returns the newest complete line's
  /// values (sim time [s], tracking error [rad]), nullopt when none came.
  std::optional<std::pair<double, double>> wait(int timeout_ms);
  /// Why the logger stopped, if it said so ("" otherwise).
  const std::string& loggerError() const { return logger_error_; }
  /// What the logger asked to be said since the last call (a slow answer).
  std::vector<std::string> takeNotices() { return std::exchange(notices_, {}); }

 private:
  int fd_;
  std::string pending_;  ///< the start of a line not yet ended
  std::string logger_error_;
  std::vector<std::string> notices_;
};

}  // namespace lagrange::tools
