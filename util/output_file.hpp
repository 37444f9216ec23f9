#pragma once
/// @file
/// Creating an output file without following a link someone planted in its
/// place. An output directory may be shared or reused: DIR/summary.json could
/// be a symbolic link to a file of the user's, DIR/run.lcm a hard link to
/// one; writing through either (std::ofstream, fopen "w", O_TRUNC) would
/// overwrite that file. So a file is always made new: a planted symbolic link
/// is refused (UnsafeOutputPath, naming the file), an old regular file is
/// unlinked (a hard link's other names keep their bytes) and the new one is
/// created with O_CREAT | O_EXCL | O_NOFOLLOW, which never follows a link.
/// Every failure names the file and says why (strerror).

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "util/error.hpp"

namespace lagrange::util {

/// A path where an output must not be written: a symbolic link, a directory,
/// a device. Bad input (exit 2), unlike a write error (exit 1).
class UnsafeOutputPath : public lagrange::BadInput {
 public:
  using lagrange::BadInput::BadInput;
};

/// "writing 'PATH' failed: No space left on device", from errno.
inline std::string ioErrorText(const std::string& what, const std::string& path, int error) {
  return what + " '" + path + "' failed: " + std::strerror(error);
}

/// Throws UnsafeOutputPath unless nothing or a regular file is at `path`.
inline void checkOutputPath(const std::string& path) {
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    throw lagrange::RuntimeFault(ioErrorText("examining", path, errno));
  }
  if (S_ISLNK(st.st_mode)) {
    char target[PATH_MAX] = {};
    const ssize_t n = readlink(path.c_str(), target, sizeof target - 1);
    throw UnsafeOutputPath("'" + path + "' is a symbolic link (to '" + std::string(target, n > 0 ? n : 0) +
                           "'); expected a regular file or nothing there: outputs are never written "
                           "through a link. Remove the link or choose another --out directory");
  }
  if (!S_ISREG(st.st_mode))
    throw UnsafeOutputPath("'" + path +
                           "' is not a regular file; expected a regular file or nothing there (an output "
                           "of a run goes there)");
}

/// Creates `path` anew, replacing a regular file (see the file comment);
/// returns the open descriptor (close-on-exec).
inline int createOutputFile(const std::string& path, mode_t mode = 0644) {
  checkOutputPath(path);
  if (unlink(path.c_str()) != 0 && errno != ENOENT)
    throw lagrange::RuntimeFault(ioErrorText("replacing", path, errno));
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
  if (fd >= 0) return fd;
  const int error = errno;
  if (error == EEXIST || error == ELOOP)  // something was put there between the unlink and the open
    throw UnsafeOutputPath("'" + path + "' reappeared while it was being created (" + std::strerror(error) +
                           "); expected nothing else to write the output directory during a run");
  throw lagrange::RuntimeFault(ioErrorText("creating", path, error));
}

/// Opens `path` to append to, creating it if missing, never through a link
/// (O_NOFOLLOW) and never into a file with other names (a hard link to a
/// user's file): UnsafeOutputPath naming it. Returns the descriptor (close-on-exec).
inline int openOutputFileToAppend(const std::string& path, mode_t mode = 0644) {
  const int fd =
      ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, mode);
  if (fd < 0) {
    const int error = errno;
    if (error == ELOOP)
      throw UnsafeOutputPath("'" + path + "' is a symbolic link; refusing to write through it");
    throw lagrange::RuntimeFault(ioErrorText("opening", path, error));
  }
  struct stat st {};
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink > 1) {
    ::close(fd);
    throw UnsafeOutputPath("'" + path + "' is not a file of its own (a device, a FIFO or a hard link to " +
                           "another file); refusing to write into it");
  }
  return fd;
}

/// Writes all of `data` to `fd`; throws naming `path` and the error.
inline void writeAll(int fd, const std::string& data, const std::string& path) {
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw lagrange::RuntimeFault(ioErrorText("writing", path, errno));
    done += static_cast<size_t>(n);
  }
}

/// A whole output file: created anew (createOutputFile), written, closed;
/// every step checked -- close reports a delayed write error (NFS, quota).
inline void writeOutputFile(const std::string& path, const std::string& data, mode_t mode = 0644) {
  const int fd = createOutputFile(path, mode);
  try {
    writeAll(fd, data, path);
  } catch (...) {
    close(fd);
    throw;
  }
  if (close(fd) != 0) throw lagrange::RuntimeFault(ioErrorText("writing", path, errno));
}

/// Makes directory `path` unless it is one already; throws UnsafeOutputPath
/// if a symbolic link or a file is there (files go into it next).
inline void makeOutputDirectory(const std::string& path) {
  if (mkdir(path.c_str(), 0755) == 0) return;
  if (errno != EEXIST) throw lagrange::RuntimeFault(ioErrorText("creating the directory", path, errno));
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) throw lagrange::RuntimeFault(ioErrorText("examining", path, errno));
  if (S_ISLNK(st.st_mode))
    throw UnsafeOutputPath("'" + path +
                           "' is a symbolic link; expected a directory of this run's own or nothing there: "
                           "outputs are never written through a link");
  if (!S_ISDIR(st.st_mode))
    throw UnsafeOutputPath("'" + path + "' is not a directory; expected a directory or nothing there");
}

/// Makes directory `path` and its missing parents; the last one as
/// makeOutputDirectory does (never a link: the files go there), the parents
/// as the user named them.
inline void makeOutputDirectories(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();  // "DIR/" would follow a link at DIR
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  makeOutputDirectory(path);
}

}  // namespace lagrange::util
