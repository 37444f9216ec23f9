#pragma once
/// @file
/// Appending events to a standard LCM log through LCM's own log API, so the
/// stock tools (lcm-logplayer, lcm::LogFile) read what we write.

#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagrange::logger {

class EventLog {
 public:
  explicit EventLog(const std::string& path) : file_(path, "w") {
    if (!file_.good())
      throw std::runtime_error("cannot create the log '" + path + "'; expected a writable directory");
  }
  void write(const std::string& channel, const void* data, int size, int64_t utime) {
    lcm::LogEvent ev;
    ev.eventnum = events_;
    ev.timestamp = utime;
    ev.channel = channel;
    ev.datalen = size;
    ev.data = const_cast<void*>(data);
    if (file_.writeEvent(&ev) != 0) throw std::runtime_error("writing the log failed (disk full?)");
    ++events_;
  }
  /// Encode an LCM message and append it.
  template <class Msg>
  void writeMessage(const std::string& channel, const Msg& msg, int64_t utime) {
    std::vector<uint8_t> buffer(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
    write(channel, buffer.data(), static_cast<int>(buffer.size()), utime);
  }
  void flush() { std::fflush(file_.getFilePtr()); }
  long long events() const { return events_; }

 private:
  lcm::LogFile file_;
  long long events_ = 0;
};

}  // namespace lagrange::logger
