#pragma once
/// @file
/// A secret key on disk (docs/reliability.md, "Threat model"): 64 hex digits
/// and a newline, in a regular file only its owner can read or write, as
/// ssh wants of a private key. The launcher writes one per run (OUT/run.key)
/// and hands its path -- never the key -- to the processes (--key-file) and
/// to an external controller (LAGRANGE_KEY_FILE); `lagrange keygen` writes
/// one to share between the hosts of a run spread with --processes.

#include <string>

#include "transport/message_auth.hpp"

namespace lagrange::runtime {

/// The key in `path`. config::ConfigError naming the file and what was
/// expected when it is missing, not a regular file, readable or writable by
/// others than its owner, or not 64 hex digits.
transport::MessageKey readKeyFile(const std::string& path);

/// Creates `path` with mode 0600 and writes `key` to it. Never follows a
/// symbolic link and never replaces a file: config::ConfigError naming the
/// file if it exists or cannot be written.
void writeKeyFile(const std::string& path, const transport::MessageKey& key);

}  // namespace lagrange::runtime
