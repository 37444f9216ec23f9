#pragma once
/// @file
/// What `lagrange COMMAND --help` shows: its one-line summary and the
/// examples it ends with (tools/subcommand.hpp describeCommand), for the
/// tests that run every example as a user would type it.

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "support/launch.hpp"

namespace lagrange::testing {

struct CommandHelp {
  std::string text;                   ///< the whole --help
  std::string summary;                ///< its first line
  std::vector<std::string> examples;  ///< the lines after "Examples:", indentation removed
  bool ends_with_examples = false;    ///< nothing but the examples after "Examples:"
};

inline CommandHelp commandHelp(const std::string& command) {
  CommandHelp h;
  h.text = lagrange(command + " --help").output;
  std::istringstream lines(h.text);
  std::string line;
  std::getline(lines, h.summary);
  bool in_examples = false;
  h.ends_with_examples = false;
  while (std::getline(lines, line)) {
    if (line == "Examples:") {
      in_examples = true;
      h.ends_with_examples = true;
      continue;
    }
    if (!in_examples || line.empty()) continue;
    if (line.rfind("  ", 0) != 0) h.ends_with_examples = false;  // text after the examples
    h.examples.push_back(line.substr(line.find_first_not_of(' ')));
  }
  return h;
}

/// An example as the user types it: in `workdir`, with the built programs first on PATH.
inline RunResult runExample(const std::string& example, const std::string& workdir) {
  return shell("cd " + quote(workdir) + " && PATH=" + quote(kBin) + ":\"$PATH\" " + example);
}

}  // namespace lagrange::testing
