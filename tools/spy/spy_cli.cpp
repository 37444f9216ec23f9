/// @file
/// `lagrange spy`'s command line (tools/spy/spy.hpp).
#include <CLI/CLI.hpp>
#include <memory>

#include "tools/spy/spy.hpp"

namespace lagrange::tools {

Subcommand addSpyCommand(CLI::App& app) {
  auto spy = std::make_shared<SpyOptions>();
  CLI::App* cmd = app.add_subcommand("spy", "Watch a running scenario's traffic in lcm-spy");
  describeCommand(
      *cmd,
      "Start lcm-spy with this project's message types on a running scenario's LCM URL (joining its private "
      "network namespace), so every channel is decoded; needs a display. DIR is the output directory of a "
      "realtime run; spy waits for one to start there (lagrange run configs/rigid_2dof.yaml --mode realtime "
      "--out runs/live, in another terminal)",
      {"lagrange spy runs/live"});
  // Named DIR, and checked by runSpy (which waits for the folder and says
  // what it expected), not by CLI11 ("run: Directory does not exist").
  cmd->add_option("DIR", spy->run_dir,
                  "Output directory of a `lagrange run` going or about to (its lcm.json)");
  cmd->add_option("--lcm-url", spy->lcm_url,
                  "LCM URL to watch (default: the run's; without a run, LCM's default URL)");
  spy->wait_seconds = 600;
  cmd->add_option("--wait", spy->wait_seconds,
                  "Seconds to wait for a run to be going in DIR (0: look once; Ctrl-C stops the wait); 0 to "
                  "86400")
      ->capture_default_str()
      ->type_name("SECONDS")
      ->check(CLI::Range(0.0, 86400.0).description(""));
  cmd->add_flag("--print-command", spy->print_only, "Print the java command line instead of running it");
  return {cmd, [spy](const Invocation&) { return runSpy(*spy); }};
}

}  // namespace lagrange::tools
