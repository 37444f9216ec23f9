#pragma once
/// @file
/// Opening a file a user or another program named, before reading a byte of
/// it, without trusting what is there: a FIFO would block the reader for ever,
/// /dev/zero or /dev/urandom would fill its memory, a directory reads as an
/// error half-way. So the path is opened with O_NONBLOCK (opening a FIFO
/// without a writer does not wait), looked at through the descriptor (fstat:
/// what is checked is what will be read, even if the path was swapped since)
/// and refused unless it is a regular file, with the file named and what it
/// is and what was expected said. Optionally a symbolic link is refused too
/// (O_NOFOLLOW): a file inside a folder others can write, such as a sweep's
/// rows, is never legitimately a link. The one helper for every input file
/// (config/input_file.hpp reads scenarios and URDFs with it, logs/ the logs,
/// tools/sweep/ the rows and the plan); util/output_file.hpp is its twin.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

namespace lagrange::util {

/// What a file is, for a message: "a directory", "a FIFO (named pipe)", ...
inline const char* fileKindText(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

enum class Links {
  kFollow,  ///< a symbolic link to a regular file is read (a user's own paths)
  kRefuse   ///< a symbolic link is refused (files in a folder others can write)
};

/// An input file, open for reading (blocking reads again) once it was found
/// to be a regular file; closed with the object. Check ok() or error().
class InputFile {
 public:
  /// Opens `path`; `expected` says what it should be ("an LCM log file") in
  /// the error, which names the file as `shown` (the path as the user wrote
  /// it), or as `path` when empty. Never blocks, never reads.
  static InputFile open(const std::string& path, const std::string& expected, Links links = Links::kFollow,
                        const std::string& shown = "") {
    InputFile f;
    const std::string quoted = "'" + (shown.empty() ? path : shown) + "'";
    const int flags = O_RDONLY | O_NONBLOCK | O_CLOEXEC | (links == Links::kRefuse ? O_NOFOLLOW : 0);
    const int fd = ::open(path.c_str(), flags);
    if (fd < 0) {
      const int error = errno;
      struct stat st {};
      // O_NOFOLLOW on a link fails with ELOOP: say what it is, not "too many levels".
      if (error == ELOOP && links == Links::kRefuse && lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode))
        f.error_ = quoted + " is a symbolic link; expected " + expected +
                   " (a regular file: links are not followed here, in a folder others may write)";
      else
        f.error_ = "cannot read " + quoted + " (" + std::strerror(error) + "); expected " + expected;
      return f;
    }
    struct stat st {};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      f.error_ = quoted + " is " + fileKindText(st.st_mode) + "; expected " + expected + " (a regular file)";
      ::close(fd);
      return f;
    }
    // A regular file never blocks; reads report errors instead of EAGAIN from here on.
    (void)fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    f.fd_ = fd;
    f.size_ = static_cast<long long>(st.st_size);
    f.owner_ = st.st_uid;
    return f;
  }

  InputFile() = default;
  ~InputFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  InputFile(InputFile&& other) noexcept
      : fd_(std::exchange(other.fd_, -1)),
        size_(other.size_),
        owner_(other.owner_),
        error_(std::move(other.error_)) {}
  InputFile& operator=(InputFile&& other) noexcept {
    if (this != &other) {
      if (fd_ >= 0) ::close(fd_);
      fd_ = std::exchange(other.fd_, -1);
      size_ = other.size_;
      owner_ = other.owner_;
      error_ = std::move(other.error_);
    }
    return *this;
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  bool ok() const { return fd_ >= 0; }
  /// Why it was not opened: names the file, what it is and what was expected.
  const std::string& error() const { return error_; }
  int fd() const { return fd_; }
  /// Its size when it was opened [bytes].
  long long size() const { return size_; }
  /// The user owning it.
  uid_t owner() const { return owner_; }
  /// The descriptor, now the caller's to close (e.g. for fdopen).
  int release() { return std::exchange(fd_, -1); }

 private:
  int fd_ = -1;
  long long size_ = 0;
  uid_t owner_ = 0;
  std::string error_;
};

}  // namespace lagrange::util
