/// @file
/// `lagrange view`'s command line (tools/view/view.hpp).
#include <CLI/CLI.hpp>
#include <memory>

#include "tools/view/view.hpp"

namespace lagrange::tools {

Subcommand addViewCommand(CLI::App& app) {
  auto view = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand("view", "Draw the arm in a web browser, from a log or live");
  describeCommand(
      *cmd,
      "Draw the arm in a web browser: from a log (play, pause, speed, seek) or live from a running scenario "
      "(joining its private network namespace); prints the page's URL",
      {"lagrange view runs/rigid_2dof"});
  cmd->add_option("source", view->source,
                  "A run's output directory (live while the run goes, else its run.lcm) or a log file");
  cmd->add_option("--host", view->host,
                  "Address to listen on (default 127.0.0.1; others need --allow-remote)");
  cmd->add_option("--port", view->port, "Port to listen on (default 8642; 0: any free port)");
  cmd->add_flag(
      "--allow-remote", view->allow_remote,
      "Allow a --host that is not loopback: anyone who reaches it sees the run (no authentication)");
  cmd->add_option("--lcm-url", view->lcm_url,
                  "View live traffic on this LCM URL (default: the running scenario's, from its lcm.json)");
  cmd->add_option("--key-file", view->key_file,
                  "Live: the run's secret key, so that only what its processes sent is drawn (default: "
                  "the running scenario's run.key)");
  return {cmd, [view](const Invocation&) { return runView(*view); }};
}

}  // namespace lagrange::tools
