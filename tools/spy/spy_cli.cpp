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
      "run that is going (lagrange run ... --out runs/live, in another terminal)",
      {"lagrange spy runs/live"});
  cmd->add_option("run", spy->run_dir, "Output directory of a running `lagrange run` (it holds lcm.json)")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--lcm-url", spy->lcm_url,
                  "LCM URL to watch (default: the run's; without a run, LCM's default URL)");
  cmd->add_flag("--print-command", spy->print_only, "Print the java command line instead of running it");
  return {cmd, [spy](const Invocation&) { return runSpy(*spy); }};
}

}  // namespace lagrange::tools
