#pragma once
/// @file
/// An output file written as a stream -- the CSV files, plots scripts and maps
/// of report, compare and sweep -- created as util/output_file.hpp creates the
/// run's own files: a symbolic link planted at the path is refused
/// (UnsafeOutputPath), an old regular file replaced, the new one opened with
/// O_CREAT | O_EXCL | O_NOFOLLOW. std::ofstream cannot open a descriptor, so
/// the stream buffer is libstdc++'s stdio_filebuf over the descriptor (GCC
/// and Clang on Debian both use libstdc++), which closes it when done.

#include <ext/stdio_filebuf.h>
#include <ostream>
#include <stdexcept>
#include <string>

#include "util/error.hpp"
#include "util/output_file.hpp"

namespace lagrange::util {

class OutputStream : public std::ostream {
 public:
  /// @throws UnsafeOutputPath for a link or a non-regular file at `path`,
  /// lagrange::RuntimeFault (naming the path and the reason) if it cannot be made.
  explicit OutputStream(const std::string& path)
      : std::ostream(nullptr), path_(path), buffer_(createOutputFile(path), std::ios::out) {
    rdbuf(&buffer_);
  }

  /// Flushes and closes; throws naming the file and the error (a full disk)
  /// if anything written was lost. The destructor closes too, silently.
  void close() {
    flush();
    const bool written = good();
    const int error = errno;
    if (buffer_.close() == nullptr || !written)
      throw lagrange::RuntimeFault(ioErrorText("writing", path_, error));
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  __gnu_cxx::stdio_filebuf<char> buffer_;
};

}  // namespace lagrange::util
