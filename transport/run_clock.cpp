#include "transport/run_clock.hpp"

#include <cerrno>
#include <chrono>
#include <cstdlib>

#include "transport/messages.hpp"

namespace lagrange::transport {

namespace {

int64_t wallUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

int64_t offsetFromEnvironmentOrMeasured() {
  if (const char* text = std::getenv(kClockOffsetVariable)) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(text, &end, 10);
    if (end != text && *end == '\0' && errno == 0) return v;
  }
  return wallUs() - monotonicUs();
}

}  // namespace

int64_t monotonicUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

int64_t clockOffsetUs() {
  static const int64_t offset = offsetFromEnvironmentOrMeasured();
  return offset;
}

int64_t nowUtime() { return monotonicUs() + clockOffsetUs(); }

}  // namespace lagrange::transport
