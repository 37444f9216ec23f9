#pragma once
/// @file
/// Appending events to a standard LCM log through LCM's own log API, so the
/// stock tools (lcm-logplayer, lcm::LogFile) read what we write.
///
/// The file is created with util::createOutputFile (never through a link
/// planted in the output directory) and handed to LCM's writer as a stream
/// of our own, because lcm::LogFile opens its path with fopen, which follows
/// links. Every write, flush and the close is checked: a full disk or an I/O
/// error is kept (the first one; nothing more is written after it) and
/// check(), flush() and close() throw it, naming the file and the error, so
/// the run stops and says why instead of ending with a log cut short in
/// silence. write() itself does not throw: it runs in LCM callbacks, and an
/// exception would have to unwind through LCM's C frames.

#include <lcm/eventlog.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/error.hpp"
#include "util/output_file.hpp"

namespace lagrange::logger {

class EventLog {
 public:
  explicit EventLog(const std::string& path) : path_(path) {
    const int fd = util::createOutputFile(path);
    log_.f = fdopen(fd, "wb");
    if (log_.f == nullptr) {
      const int error = errno;
      ::close(fd);
      throw lagrange::RuntimeFault(util::ioErrorText("opening", path, error));
    }
  }
  ~EventLog() {
    if (log_.f != nullptr) std::fclose(log_.f);  // unwinding from a failure already reported
  }
  EventLog(const EventLog&) = delete;
  EventLog& operator=(const EventLog&) = delete;

  void write(const std::string& channel, const void* data, int size, int64_t utime) {
    lcm_eventlog_event_t ev{};
    ev.eventnum = events_;
    ev.timestamp = utime;
    ev.channellen = static_cast<int32_t>(channel.size());
    ev.channel = const_cast<char*>(channel.c_str());
    ev.datalen = size;
    ev.data = const_cast<void*>(data);
    if (!error_.empty()) return;
    errno = 0;
    if (lcm_eventlog_write_event(&log_, &ev) != 0) {
      error_ = util::ioErrorText("writing", path_, errno != 0 ? errno : EIO);
      return;
    }
    ++events_;
  }
  /// Throws the first write error, if there was one.
  void check() const {
    if (!error_.empty()) throw lagrange::RuntimeFault(error_);
  }
  /// Encode an LCM message and append it.
  template <class Msg>
  void writeMessage(const std::string& channel, const Msg& msg, int64_t utime) {
    std::vector<uint8_t> buffer(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
    write(channel, buffer.data(), static_cast<int>(buffer.size()), utime);
  }
  void flush() {
    check();
    errno = 0;
    if (std::fflush(log_.f) != 0) fail("writing");
  }
  /// Flushes and closes the file; throws if the last bytes could not be written.
  void close() {
    check();
    FILE* f = log_.f;
    log_.f = nullptr;
    errno = 0;
    if (std::fclose(f) != 0) fail("writing");
  }
  long long events() const { return events_; }
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw lagrange::RuntimeFault(util::ioErrorText(what, path_, errno != 0 ? errno : EIO));
  }

  std::string path_;
  std::string error_;  ///< the first write error ("" none)
  lcm_eventlog_t log_{};
  long long events_ = 0;
};

}  // namespace lagrange::logger
