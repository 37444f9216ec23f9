#include "logs/out_dir_lock.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include "util/error.hpp"
#include "util/output_file.hpp"

namespace lagrange::logs {

namespace {
struct flock writeLock(short type) {
  struct flock l {};
  l.l_type = type;
  l.l_whence = SEEK_SET;  // the whole file
  return l;
}
}  // namespace

OutDirLock::OutDirLock(const std::string& dir, const std::string& who) {
  const std::string path = (std::filesystem::path(dir) / kFileName).string();
  try {
    util::checkOutputPath(path);
  } catch (const util::UnsafeOutputPath& e) {
    throw BadInput(std::string("output directory '") + dir + "': " + e.what());
  }
  // Never unlinked and re-created: a second launcher must lock the same
  // inode as the first. O_NOFOLLOW: a link planted after the check fails here.
  fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RuntimeFault(util::ioErrorText("creating the lock file", path, errno));
  for (int attempt = 0; attempt < 3; ++attempt) {
    struct flock lock = writeLock(F_WRLCK);
    if (fcntl(fd_, F_SETLK, &lock) == 0) return;
    if (errno != EACCES && errno != EAGAIN) {
      const int error = errno;
      close(fd_);
      throw RuntimeFault(util::ioErrorText("locking", path, error));
    }
    struct flock holder = writeLock(F_WRLCK);
    if (fcntl(fd_, F_GETLK, &holder) == 0 && holder.l_type != F_UNLCK) {
      close(fd_);
      throw BadInput("output directory '" + dir + "' is being written by another run (pid " +
                     std::to_string(holder.l_pid) + " holds its lock " + path +
                     "); expected a directory no other run is writing: wait for that run to "
                     "end or give " +
                     who + " another --out directory");
    }
    // The holder ended between the two calls: try again.
  }
  close(fd_);
  throw BadInput("output directory '" + dir + "': its lock " + path +
                 " is taken and released repeatedly by other runs; expected a directory no "
                 "other run is writing");
}

OutDirLock::~OutDirLock() {
  if (fd_ >= 0) close(fd_);  // releases the lock
}

}  // namespace lagrange::logs
