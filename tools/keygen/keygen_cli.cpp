/// @file
/// `lagrange keygen` (tools/keygen/keygen.hpp).
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "runtime/key_file.hpp"
#include "tools/keygen/keygen.hpp"
#include "transport/message_auth.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

Subcommand addKeygenCommand(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("keygen", "Write a secret key for a run spread over hosts");
  describeCommand(
      *cmd,
      "Write a fresh secret key (64 hex digits, mode 600) for runs spread over hosts: give the same file to "
      "each host's `lagrange run --processes ... --key-file FILE`",
      {"lagrange keygen runs/shared.key"});
  cmd->add_option("file", *file, "The key file to create (never overwritten)")->required();
  // An error ends in tools::dispatch: "lagrange keygen: ...", exit by its kind.
  return {cmd, [file](const Invocation&) {
            runtime::writeKeyFile(*file, transport::randomMessageKey());
            return static_cast<int>(kExitOk);
          }};
}

}  // namespace lagrange::tools
