#pragma once
/// @file
/// Reading a file a user named (the scenario, a URDF) without trusting it:
/// only a regular file of bounded size is read, and it is looked at (opened
/// without blocking, then fstat: util/input_file.hpp) before a byte is read,
/// so a directory, a FIFO or /dev/zero is refused at once instead of blocking
/// or filling the memory.

#include <cstdint>
#include <string>

namespace lagrange::config {

/// The scenario file: a hand-written YAML map is a few kB; 1 MiB leaves room
/// for an inline URDF (robot.urdf.xml of a resolved scenario).
inline constexpr std::uintmax_t kMaxScenarioBytes = 1u << 20;
/// A URDF file: the shipped arms are under 40 kB; meshes are separate files.
inline constexpr std::uintmax_t kMaxUrdfBytes = 16u << 20;

struct FileText {
  std::string text;   ///< the whole file, when error is empty
  std::string error;  ///< why it was not read: "'P' is a directory; expected WHAT", ...
};

/// The whole of `path` when it is a readable regular file of at most
/// max_bytes; otherwise `error` says what it is and that `expected` (e.g. "a
/// YAML scenario file") was expected. Never blocks on a FIFO, never reads
/// more than max_bytes + 1 bytes. Messages name the file as `shown` (the
/// path as the user wrote it), or as `path` when empty.
FileText readRegularFile(const std::string& path, std::uintmax_t max_bytes, const std::string& expected,
                         const std::string& shown = "");

/// "1 MiB", "16 MiB", "2.5 MiB", "800 bytes": a size for a message.
std::string sizeText(std::uintmax_t bytes);

}  // namespace lagrange::config
