#pragma once
/// @file
/// `lagrange keygen FILE`: a fresh secret key for a run spread over hosts
/// (runtime/key_file.hpp, docs/deployment.md).

#include "tools/subcommand.hpp"

namespace lagrange::tools {

/// Declares `keygen` on the front end. Exit 0, or 2 naming the file it cannot create.
Subcommand addKeygenCommand(CLI::App& app);

}  // namespace lagrange::tools
