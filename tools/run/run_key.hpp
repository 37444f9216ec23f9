#pragma once
/// @file
/// The secret key of one `lagrange run` (docs/reliability.md, "Keys"): the
/// user's --key-file, or a fresh random key in OUT/run.key that lives as long
/// as this object -- the processes read it at start and on a restart, and
/// nothing needs it once the run has ended.

#include <string>

namespace lagrange::tools {

class RunKey {
 public:
  /// `key_file` non-empty: that file (already checked by readKeyFile).
  /// Empty: a fresh key in OUT/run.key (a leftover of a killed run is
  /// replaced; a link there is removed, never followed). config::ConfigError
  /// if the file cannot be written.
  RunKey(const std::string& key_file, const std::string& out_dir);
  ~RunKey();
  RunKey(const RunKey&) = delete;
  RunKey& operator=(const RunKey&) = delete;

  /// Absolute path of the key file, for --key-file and LAGRANGE_KEY_FILE.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  bool owned_ = false;  ///< made here: removed at the end
};

}  // namespace lagrange::tools
