#include "tools/run/run_key.hpp"

#include <unistd.h>

#include <filesystem>

#include "runtime/key_file.hpp"

namespace lagrange::tools {

RunKey::RunKey(const std::string& key_file, const std::string& out_dir) {
  if (!key_file.empty()) {
    path_ = std::filesystem::absolute(key_file).string();
    return;
  }
  path_ = std::filesystem::absolute(std::filesystem::path(out_dir) / "run.key").string();
  unlink(path_.c_str());  // a killed run's key; unlink removes a link itself, not its target
  runtime::writeKeyFile(path_, transport::randomMessageKey());
  owned_ = true;
}

RunKey::~RunKey() {
  if (owned_) unlink(path_.c_str());
}

}  // namespace lagrange::tools
