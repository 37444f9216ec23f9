#pragma once
/// @file
/// The seam between `lagrange`'s front end and its subcommands. Each command
/// folder (tools/<command>/) declares its options on the front end's CLI11
/// app and hands back what runs it; tools/lagrange.cpp only lists the commands
/// and dispatches to the one the user named. A new subcommand is a new folder
/// and one line in that list.

#include <functional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace lagrange::tools {

/// What a command may need of the program that runs it.
struct Invocation {
  std::vector<std::string> argv;  ///< as given, argv[0] replaced by the program's absolute path
  std::string self_exe;           ///< this program's absolute path (for re-executing it)
  /// False only in the benchmark's build of the front end
  /// (LAGRANGE_BENCH_UNSIGNED, bench/CMakeLists.txt): runs without a key.
  bool sign = true;
};

/// One subcommand on the command line: `cli` is set when the user named it
/// (CLI11's operator bool), `run` runs it with the parsed options and returns
/// the exit code (util/error.hpp).
struct Subcommand {
  CLI::App* cli = nullptr;
  std::function<int(const Invocation&)> run;
};

/// What each command folder provides: declares the command and its options on
/// `app` (bound to state the returned `run` owns).
using AddSubcommand = Subcommand (*)(CLI::App& app);

/// The end of `lagrange COMMAND --help`, after its one-line summary (the
/// command's description, which `lagrange --help` lists) and its options:
/// what the command does in full, wrapped to 80 columns, then "Examples:"
/// with one command line each -- run from the repository's root, they work
/// (tests/integration/help_test.cpp runs every one).
void describeCommand(CLI::App& cmd, const std::string& details, const std::vector<std::string>& examples);

}  // namespace lagrange::tools
