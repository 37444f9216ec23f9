#pragma once
/// @file
/// `lagrange spy [RUN_DIR] [--lcm-url URL]`: LCM's own lcm-spy with this
/// project's message types, on the LCM URL of a running scenario. Debian's
/// lcm-spy script cannot be used as it is: it passes -Xincgc, which current
/// Java refuses, and its class path lacks user types, so every channel
/// would show as undecodable. A run started by `lagrange run` leaves
/// OUT/lcm.json (its URL and, for a private network namespace, the pid whose
/// namespace to join), so `lagrange spy OUT` sees that run's traffic.

#include <optional>
#include <string>
#include <vector>

#include "tools/subcommand.hpp"

namespace lagrange::tools {

/// Where a running scenario's traffic is: OUT/lcm.json.
struct RunEndpoint {
  std::string lcm_url;
  int64_t run_id = 0;
  std::optional<long> netns_pid;  ///< a process in the run's private network namespace
  /// The launcher (`lagrange run`): the run is going while it lives
  /// (absent in files written before it was added).
  std::optional<long> launcher_pid;
};

/// Writes OUT/lcm.json. @throws RuntimeFault if it cannot be written.
void writeEndpoint(const std::string& out_dir, const RunEndpoint& endpoint);
/// @throws BadInput naming the file and what is wrong with it.
RunEndpoint readEndpoint(const std::string& out_dir);

/// The java command line of lcm-spy with the LCM jar, jchart2d and this
/// project's types jar. @throws BadInput naming a missing jar and its Debian package.
std::vector<std::string> spyCommand(const std::string& lcm_url);

struct SpyOptions {
  std::string run_dir;  ///< empty: no run (use lcm_url, or LCM's default)
  std::string lcm_url;  ///< overrides the run's URL
  bool print_only = false;
};

/// Joins the run's network namespace and replaces this process with lcm-spy;
/// returns an exit code only on failure (or with print_only).
int runSpy(const SpyOptions& options);

/// Declares `spy` and its options on the front end (tools/spy/spy_cli.cpp).
Subcommand addSpyCommand(CLI::App& app);

}  // namespace lagrange::tools
