/// @file
/// `lagrange keys` (tools/keys/keys.hpp).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "config/key_reference.hpp"
#include "tools/keys/key_listing.hpp"
#include "tools/keys/keys.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

namespace {
struct KeysCommandLine {
  std::vector<std::string> sections;
  bool markdown = false;
};
}  // namespace

Subcommand addKeysCommand(CLI::App& app) {
  auto options = std::make_shared<KeysCommandLine>();
  CLI::App* cmd = app.add_subcommand("keys", "List the scenario keys: type, default, meaning");
  describeCommand(
      *cmd,
      "Every key a scenario file may hold: its type, default, range and meaning (docs/configuration.md)",
      {"lagrange keys plant", "lagrange keys controller.stages"});
  cmd->add_option("section", options->sections,
                  "Only the keys in these sections or under these keys (e.g. plant, controller.stages)");
  cmd->add_flag("--markdown", options->markdown,
                "Print docs/configuration.md's table of keys (all keys: no sections with it)");
  // A section no key is in ends in tools::dispatch: "lagrange keys: ...", exit 2.
  return {cmd, [options](const Invocation&) {
            if (options->markdown && !options->sections.empty())
              throw BadInput("--markdown prints the whole table; expected no sections with it");
            std::cout << (options->markdown ? config::keyReferenceMarkdown() : keyListing(options->sections));
            return static_cast<int>(kExitOk);
          }};
}

}  // namespace lagrange::tools
