#pragma once
/// @file
/// How a subcommand ends on an exception: the message on stderr after the
/// command's name, and the exit code of the error's kind (util/error.hpp).

#include <exception>
#include <iostream>
#include <string>

#include "util/error.hpp"
#include "util/terminal_text.hpp"

namespace lagrange::tools {

/// Prints "WHO: what" on stderr and returns exitCodeOf(e): 2 for bad input,
/// 1 for a runtime fault or anything else. The message may quote a file, a
/// log or a program (a key of a scenario, a value of a log): its control
/// characters are escaped (util/terminal_text.hpp), its lines kept.
inline int failWith(const std::string& who, const std::exception& e) {
  std::cerr << who << ": " << util::terminalSafeLines(e.what()) << "\n";
  return exitCodeOf(e);
}

}  // namespace lagrange::tools
