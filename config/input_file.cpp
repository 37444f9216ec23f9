#include "config/input_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "util/input_file.hpp"

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

FileText readRegularFile(const std::string& path, std::uintmax_t max_bytes, const std::string& expected,
                         const std::string& shown) {
  FileText out;
  const util::InputFile file = util::InputFile::open(path, expected, util::Links::kFollow, shown);
  if (!file.ok()) {
    out.error = file.error();
    return out;
  }
  const std::string quoted = "'" + (shown.empty() ? path : shown) + "'";
  const auto too_big = [&](std::uintmax_t size) {
    return quoted + " is " + (size > max_bytes ? "larger than " : "") + sizeText(size) + "; expected " +
           expected + " of at most " + sizeText(max_bytes);
  };
  if (static_cast<std::uintmax_t>(file.size()) > max_bytes) {
    out.error = too_big(static_cast<std::uintmax_t>(file.size()));
    return out;
  }
  // Read at most one byte past the limit: a file that grew since it was opened is caught, not read whole.
  char buf[65536];
  while (out.text.size() <= max_bytes) {
    const ssize_t got = read(file.fd(), buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      out.error = "cannot read " + quoted + " (" + std::strerror(errno) + "); expected " + expected;
      break;
    }
    if (got == 0) break;
    out.text.append(buf, static_cast<size_t>(got));
  }
  if (out.error.empty() && out.text.size() > max_bytes) out.error = too_big(out.text.size());
  if (!out.error.empty()) out.text.clear();
  return out;
}

}  // namespace lagrange::config
