/// @file
/// `lagrange replay`'s command line and its report of the result
/// (tools/replay/replay.hpp).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "tools/command_error.hpp"
#include "tools/replay/replay.hpp"
#include "tools/replay/replay_external.hpp"
#include "util/error.hpp"
#include "wiring/netns.hpp"

namespace lagrange::tools {

namespace {
struct ReplayCommandLine {
  std::string log;
  std::string component = "controller";
  std::vector<std::string> overrides;
};

int replay(const ReplayCommandLine& o, const std::vector<std::string>& self_argv) {
  // An external controller is replayed by running it again, on a bus of its
  // own: in a private network namespace, as `lagrange run` does.
  if (o.component == "controller" && !wiring::insidePrivateNetns() && isExternalControllerLog(o.log)) {
    const std::string why = wiring::reexecInPrivateNetns(self_argv);  // returns only on failure
    std::cerr << "lagrange replay: " << why << "; install util-linux to replay an external controller\n";
    return kExitFailed;
  }
  try {
    const ReplayResult r = o.component == "actuator" ? replayActuator(o.log, o.overrides)
                           : o.component == "plant"  ? replayPlant(o.log, o.overrides)
                                                     : replayController(o.log, o.overrides);
    for (const auto& w : r.warnings) std::cerr << "lagrange replay: warning: " << w << "\n";
    if (r.divergence) {
      std::cout << "lagrange replay: " << o.component << " DIVERGED after " << r.commands << " outputs at "
                << *r.divergence << "\n";
      return kExitFailed;
    }
    std::cout << "lagrange replay: " << o.component << " reproduced all " << r.commands
              << " recorded outputs bit for bit (" << r.events << " events read)\n";
    return kExitOk;
  } catch (const ReplayError& e) {  // anything else ends in tools::dispatch, the same way
    for (const auto& w : e.warnings()) std::cerr << "lagrange replay: warning: " << w << "\n";
    return failWith("lagrange replay", e);
  }
}
}  // namespace

Subcommand addReplayCommand(CLI::App& app) {
  auto o = std::make_shared<ReplayCommandLine>();
  CLI::App* cmd = app.add_subcommand(
      "replay",
      "Feed a component's recorded inputs from an LCM log into its core and compare every output with the "
      "recorded one; print the first divergence (tick, time, field, both values); exit 1 on any");
  cmd->add_option("log", o->log, "LCM log written by lagrange run (run.lcm)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--component", o->component,
                  "Component to replay: controller (default; CONTROL_COMMAND), actuator (ACTUATOR_STATE) or "
                  "plant (PLANT_TRUTH, PLANT_POSITION, PLANT_MOTOR, PLANT_RATE)")
      ->check(CLI::IsMember({"controller", "actuator", "plant"}));
  cmd->add_option("--set", o->overrides,
                  "Override a key of the logged scenario before replaying (e.g. to check that a "
                  "changed gain is caught); repeatable");
  return {cmd, [o](const Invocation& inv) { return replay(*o, inv.argv); }};
}

}  // namespace lagrange::tools
