#pragma once
/// @file
/// The front end's whole job: declare the subcommands it is given on one
/// CLI11 app, parse the command line, and run the one the user named.

#include <vector>

#include "tools/subcommand.hpp"

namespace lagrange::tools {

/// The program's name and one-line description, as --help shows them.
struct FrontEnd {
  const char* name = "lagrange";
  const char* description = "lagrange: observer-less output-feedback tracking testbed (LCM; ODE or MuJoCo)";
  bool sign = true;  ///< Invocation::sign
};

/// Declares `commands` (in --help's order), parses argv and returns the named
/// command's exit code; 0 for --help, 2 for a command line CLI11 refuses.
int dispatch(int argc, char** argv, const std::vector<AddSubcommand>& commands,
             const FrontEnd& front_end = {});

}  // namespace lagrange::tools
