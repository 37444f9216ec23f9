#include "runtime/key_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "config/scenario.hpp"
#include "util/error.hpp"

namespace lagrange::runtime {

namespace {
// Enough for 64 digits, a CR LF and nothing else worth reading.
constexpr off_t kMaxKeyFileBytes = 128;

// The file is wrong (missing, open to others, not a key): bad input.
[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw config::ConfigError("key file '" + path + "': " + what);
}

// Reading or writing a file that is right failed (EIO, ENOSPC): a fault.
[[noreturn]] void ioFault(const std::string& path, const std::string& what) {
  throw RuntimeFault("key file '" + path + "': " + what);
}

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) close(fd);
  }
};
}  // namespace

transport::MessageKey readKeyFile(const std::string& path) {
  const Fd file{open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (file.fd < 0)
    fail(path, std::string(std::strerror(errno)) + "; expected a file made by `lagrange keygen`");
  struct stat st {};
  if (fstat(file.fd, &st) != 0) ioFault(path, std::strerror(errno));
  if (!S_ISREG(st.st_mode)) fail(path, "not a regular file; expected a file of 64 hex digits");
  if ((st.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%03o", static_cast<unsigned>(st.st_mode & 0777));
    fail(path, std::string("open to others (mode ") + mode + "); expected mode 600 or 400: chmod 600 '" +
                   path + "'");
  }
  if (st.st_size > kMaxKeyFileBytes)
    fail(path, std::to_string(st.st_size) + " bytes; expected 64 hex digits and a newline");
  char buf[kMaxKeyFileBytes + 1];
  const ssize_t got = read(file.fd, buf, sizeof buf);
  if (got < 0) ioFault(path, std::strerror(errno));
  std::string text(buf, static_cast<size_t>(got));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  transport::MessageKey key;
  if (!transport::fromHex(text, key)) fail(path, "not a key; expected exactly 64 hex digits and a newline");
  return key;
}

void writeKeyFile(const std::string& path, const transport::MessageKey& key) {
  const Fd file{open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600)};
  if (file.fd < 0)
    fail(path, std::string("cannot create it: ") + std::strerror(errno) +
                   (errno == EEXIST ? " (a key file is never overwritten; remove it or name another)" : ""));
  const std::string text = transport::toHex(key) + "\n";
  if (write(file.fd, text.data(), text.size()) != static_cast<ssize_t>(text.size()) || fsync(file.fd) != 0)
    ioFault(path, std::string("cannot write it: ") + std::strerror(errno));
}

}  // namespace lagrange::runtime
