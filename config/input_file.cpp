#include "config/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace lagrange::config {

std::string sizeText(std::uintmax_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  char buf[64];
  const double mib = static_cast<double>(bytes) / (1024.0 * 1024.0);
  if (mib >= 1.0)
    std::snprintf(buf, sizeof buf, "%.3g MiB", mib);
  else
    std::snprintf(buf, sizeof buf, "%.3g KiB", static_cast<double>(bytes) / 1024.0);
  return buf;
}

namespace {
const char* kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}
}  // namespace

FileText readRegularFile(const std::string& path, std::uintmax_t max_bytes, const std::string& expected,
                         const std::string& shown) {
  FileText out;
  const std::string quoted = "'" + (shown.empty() ? path : shown) + "'";
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) {
    out.error = "cannot read " + quoted + " (" + std::strerror(errno) + "); expected " + expected;
    return out;
  }
  if (!S_ISREG(st.st_mode)) {
    out.error = quoted + " is " + kindOf(st.st_mode) + "; expected " + expected + " (a regular file)";
    return out;
  }
  const auto too_big = [&](std::uintmax_t size) {
    return quoted + " is " + (size > max_bytes ? "larger than " : "") + sizeText(size) + "; expected " +
           expected + " of at most " + sizeText(max_bytes);
  };
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    out.error = too_big(static_cast<std::uintmax_t>(st.st_size));
    return out;
  }
  // O_NONBLOCK: should the path have been swapped for a FIFO since stat, open does not wait for a writer.
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    out.error = "cannot read " + quoted + " (" + std::strerror(errno) + "); expected " + expected;
    return out;
  }
  struct stat opened {};
  if (fstat(fd, &opened) != 0 || !S_ISREG(opened.st_mode)) {
    close(fd);
    out.error = quoted + " is " + kindOf(opened.st_mode) + "; expected " + expected + " (a regular file)";
    return out;
  }
  // Read at most one byte past the limit: a file that grew since stat is caught, not read whole.
  char buf[65536];
  while (out.text.size() <= max_bytes) {
    const ssize_t got = read(fd, buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      out.error = "cannot read " + quoted + " (" + std::strerror(errno) + "); expected " + expected;
      break;
    }
    if (got == 0) break;
    out.text.append(buf, static_cast<size_t>(got));
  }
  close(fd);
  if (out.error.empty() && out.text.size() > max_bytes) out.error = too_big(out.text.size());
  if (!out.error.empty()) out.text.clear();
  return out;
}

}  // namespace lagrange::config
