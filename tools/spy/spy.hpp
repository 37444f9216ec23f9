#pragma once
/// @file
/// `lagrange spy [RUN_DIR] [--lcm-url URL] [--wait S]`: LCM's own lcm-spy with this
/// project's message types, on the LCM URL of a running scenario. Debian's
/// lcm-spy script cannot be used as it is: it passes -Xincgc, which current
/// Java refuses, and its class path lacks user types, so every channel
/// would show as undecodable. A run started by `lagrange run` leaves
/// OUT/lcm.json (its URL and, for a private network namespace, the pid whose
/// namespace to join), so `lagrange spy OUT` sees that run's traffic -- and
/// waits for it when started first (live_run.hpp).

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

/// A run folder is data, never instructions: lcm.json is read as what
/// `lagrange run` writes and nothing else. Only a regular file of at most
/// 64 KiB, a JSON object of lcm_url, run_id, netns_pid and launcher_pid; the
/// URL as the launcher writes it (runUrlProblem); pids positive, and
/// netns_pid (the launcher takes the namespace from itself) null or the
/// launcher's. Anything else is refused whole: a folder cannot make view or
/// spy open a URL of its choice (LCM's file provider in write mode would
/// empty a file) or join another process's namespaces.
/// @throws BadInput naming the file, the field and what was expected.
RunEndpoint readEndpoint(const std::string& out_dir);

/// "" when `url` has the one form `lagrange run` writes into lcm.json --
/// `udpm://A.B.C.D:PORT` with A.B.C.D a multicast IPv4 address
/// (224.0.0.0-239.255.255.255, decimal, no leading zeros), PORT 1-65535
/// and at most the query `?ttl=N`, N 0-255 -- else what is wrong with it.
/// Checked character by character: nothing else (another provider, another
/// option, a second `?`, a NUL, spaces) passes.
std::string runUrlProblem(const std::string& url);

/// The run's launcher still runs: the process lives and is a `lagrange`
/// (its first argument's file name: a pid of a run long finished may have
/// been given to another program).
bool launcherAlive(long pid);

/// The java command line of lcm-spy with the LCM jar, jchart2d and this
/// project's types jar. @throws BadInput naming a missing jar and its Debian package.
std::vector<std::string> spyCommand(const std::string& lcm_url);

struct SpyOptions {
  std::string run_dir;  ///< empty: no run (use lcm_url, or LCM's default)
  std::string lcm_url;  ///< overrides the run's URL
  bool print_only = false;
  /// How long to wait for a run to be going in run_dir (live_run.hpp); 0: look once.
  double wait_seconds = 0.0;
};

/// Waits for a run in run_dir (unless print_only), joins its network
/// namespace and replaces this process with lcm-spy; returns an exit code
/// only on failure (or with print_only).
int runSpy(const SpyOptions& options);

/// Declares `spy` and its options on the front end (tools/spy/spy_cli.cpp).
Subcommand addSpyCommand(CLI::App& app);

}  // namespace lagrange::tools
