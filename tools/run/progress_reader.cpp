#include "tools/run/progress_reader.hpp"

#include <poll.h>
#include <unistd.h>

#include <cstring>
#include <sstream>

#include "logger/error_line.hpp"

namespace lagrange::tools {

std::optional<std::pair<double, double>> ProgressReader::wait(int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  if (poll(&p, 1, timeout_ms) <= 0) return std::nullopt;
  char buf[4096];
  const ssize_t got = read(fd_, buf, sizeof buf);
  if (got <= 0) return std::nullopt;
  pending_.append(buf, static_cast<size_t>(got));
  std::optional<std::pair<double, double>> newest;
  for (size_t end; (end = pending_.find('\n')) != std::string::npos; pending_.erase(0, end + 1)) {
    const std::string line = pending_.substr(0, end);
    if (line.rfind(logger::kLoggerErrorPrefix, 0) == 0) {
      logger_error_ = line.substr(std::strlen(logger::kLoggerErrorPrefix));
      continue;
    }
    if (line.rfind(logger::kLoggerNoticePrefix, 0) == 0) {
      if (notices_.size() < 100) notices_.push_back(line.substr(std::strlen(logger::kLoggerNoticePrefix)));
      continue;
    }
    std::istringstream in(line);
    double t = 0.0, error = 0.0;
    if (in >> t >> error) newest = std::make_pair(t, error);
  }
  return newest;
}

}  // namespace lagrange::tools
