#pragma once
/// @file
/// The secret key of one `lagrange run` (docs/reliability.md, "Threat
/// model"), in OUT/run.key for as long as this object lives -- the processes
/// read it at start and on a restart, and nothing needs it once the run has
/// ended. It is always this run's own: a fresh random key, or, when the user
/// gives a key file (shared by runs, or by the hosts of a run spread with
/// --processes), a key derived from it and a value fresh for this run
/// (transport::deriveRunKey). A key file given by the user is never handed to
/// the processes itself, so nothing recorded from another run under it is
/// accepted by this one.

#include <string>

#include "transport/message_auth.hpp"

namespace lagrange::tools {

class RunKey {
 public:
  /// Writes `key` to OUT/run.key, mode 600 (a leftover of a killed run is
  /// replaced; a link there is removed, never followed). config::ConfigError
  /// if the file cannot be written.
  RunKey(const transport::MessageKey& key, const std::string& out_dir);
  ~RunKey();
  RunKey(const RunKey&) = delete;
  RunKey& operator=(const RunKey&) = delete;

  /// Absolute path of the key file, for --key-file and LAGRANGE_KEY_FILE.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace lagrange::tools
