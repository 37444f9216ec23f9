#include "tools/run/run_key.hpp"

#include <unistd.h>

#include <filesystem>

#include "runtime/key_file.hpp"

namespace lagrange::tools {

RunKey::RunKey(const transport::MessageKey& key, const std::string& out_dir) {
  path_ = std::filesystem::absolute(std::filesystem::path(out_dir) / "run.key").string();
  unlink(path_.c_str());  // a killed run's key; unlink removes a link itself, not its target
  runtime::writeKeyFile(path_, key);
}

RunKey::~RunKey() { unlink(path_.c_str()); }

}  // namespace lagrange::tools
