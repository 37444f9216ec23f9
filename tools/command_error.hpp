#pragma once
/// @file
/// How a subcommand ends on an exception: the message on stderr after the
/// command's name, and the exit code of the error's kind (util/error.hpp).

#include <exception>
#include <iostream>
#include <string>

#include "util/error.hpp"

namespace lagrange::tools {

/// Prints "WHO: what" on stderr and returns exitCodeOf(e): 2 for bad input,
/// 1 for a runtime fault or anything else.
inline int failWith(const std::string& who, const std::exception& e) {
  std::cerr << who << ": " << e.what() << "\n";
  return exitCodeOf(e);
}

}  // namespace lagrange::tools
