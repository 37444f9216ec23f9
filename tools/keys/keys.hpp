#pragma once
/// @file
/// `lagrange keys [SECTION...] [--markdown]`: every key a scenario file may
/// hold, with its type, default, range and meaning (config/key_table.hpp);
/// `--markdown` prints docs/configuration.md's table.

#include "tools/subcommand.hpp"

namespace lagrange::tools {

/// Declares `keys` on the front end. Exit 0, or 2 for a section no key is in.
Subcommand addKeysCommand(CLI::App& app);

}  // namespace lagrange::tools
