/// @file
/// `lagrange replay`'s command line and its report of the result
/// (tools/replay/replay.hpp).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include "tools/command_error.hpp"
#include "tools/replay/replay.hpp"
#include "tools/replay/replay_external.hpp"
#include "tools/replay/shell_words.hpp"
#include "util/error.hpp"
#include "util/terminal_text.hpp"
#include "wiring/netns.hpp"

namespace lagrange::tools {

namespace {
struct ReplayCommandLine {
  std::string log;
  std::string component = "controller";
  const CLI::Option* component_option = nullptr;  // counted: was --component given?
  std::vector<std::string> overrides;
  std::vector<std::string> external_command;  // after --: the program replaying an external controller
};

// Replays one component and prints its result; the exit code.
int replayComponent(const ReplayCommandLine& o, const std::string& component) {
  try {
    const ReplayResult r = component == "actuator" ? replayActuator(o.log, o.overrides)
                           : component == "plant"  ? replayPlant(o.log, o.overrides, o.external_command)
                                                   : replayController(o.log, o.overrides, o.external_command);
    for (const auto& w : r.warnings)
      std::cerr << "lagrange replay: warning: " << util::terminalSafeLines(w) << "\n";
    if (r.divergence) {
      std::cout << "lagrange replay: " << component << " DIVERGED after " << r.commands << " outputs at "
                << util::terminalSafeLines(*r.divergence) << "\n";
      return kExitFailed;
    }
    std::cout << "lagrange replay: " << component << " reproduced all " << r.commands
              << " recorded outputs bit for bit (" << r.events << " events read)\n";
    return kExitOk;
  } catch (const ReplayError& e) {  // anything else ends in tools::dispatch, the same way
    for (const auto& w : e.warnings())
      std::cerr << "lagrange replay: warning: " << util::terminalSafeLines(w) << "\n";
    return failWith("lagrange replay", e);
  }
}

// Why the log's external controller is not replayed, its command (not run)
// and how to replay it on purpose.
std::string notRun(const ReplayCommandLine& o, const LoggedController& logged) {
  return "the log's controller is external, and replay runs no program a log names; the log's command "
         "(not run) is:\n    " +
         shellWords(logged.command) +
         "\n  to replay the controller, name the program yourself after --: lagrange replay " +
         shellWord(o.log) + " -- COMMAND ARGS...";
}

int replay(const ReplayCommandLine& o, const std::vector<std::string>& self_argv) {
  const bool command_given = !o.external_command.empty();
  if (command_given && std::find(self_argv.begin(), self_argv.end(), "--") == self_argv.end())
    return failWith("lagrange replay",
                    BadInput("unexpected arguments after the log: " + shellWords(o.external_command) +
                             "; expected nothing there, or -- and the command of an external controller "
                             "to replay (lagrange replay LOG -- COMMAND ARGS...)"));
  const LoggedController logged = loggedController(o.log);
  if (command_given) {
    if (o.component != "controller" && o.component != "plant")
      return failWith("lagrange replay",
                      BadInput("a command after -- replays an external controller or (with --component "
                               "plant) an external plant; --component " +
                               o.component + " runs none (drop the command)"));
    const LoggedController program = o.component == "plant" ? loggedController(o.log, "plant") : logged;
    if (!program.type.empty() && !program.external())
      return failWith("lagrange replay",
                      BadInput("the log's " + o.component + " is '" + program.type +
                               "', which replay builds itself; a command after -- is for a log whose " +
                               o.component + ".type is external, and none was run"));
    // The program runs on a bus of its own: in a private network namespace, as `lagrange run` does.
    if (!wiring::insidePrivateNetns()) {
      const std::string why = wiring::reexecInPrivateNetns(self_argv);  // returns only on failure
      std::cerr << "lagrange replay: " << why << "; install util-linux to replay an external " << o.component
                << "\n";
      return kExitFailed;
    }
    return replayComponent(o, o.component);
  }
  if (o.component == "controller" && logged.external()) {
    if (o.component_option->count() > 0)  // asked for by name: nothing else would answer the question
      return failWith("lagrange replay", BadInput("controller NOT replayed: " + notRun(o, logged)));
    std::cout << "lagrange replay: controller NOT replayed: " << notRun(o, logged)
              << "\n  the actuator and the plant are replayed instead\n";
    const int actuator = replayComponent(o, "actuator");
    const int plant = replayComponent(o, "plant");
    const int worst = std::max(actuator, plant);  // bad input (2) before a divergence (1)
    if (worst != 0) return worst;
    // Never 0: a CI job replaying the log to guard its controller must not
    // pass without the controller having been replayed.
    std::cerr << "lagrange replay: exit 2: the controller was not replayed (name its program after --, or "
                 "--component actuator or plant to replay only those)\n";
    return kExitBadInput;
  }
  return replayComponent(o, o.component);
}
}  // namespace

Subcommand addReplayCommand(CLI::App& app) {
  auto o = std::make_shared<ReplayCommandLine>();
  CLI::App* cmd = app.add_subcommand("replay", "Replay a log through a component, bit for bit");
  describeCommand(
      *cmd,
      "Feed a component's recorded inputs from an LCM log into its core and compare every output with the "
      "recorded one; print the first divergence (tick, time, field, both values); exit 1 on any, 2 when the "
      "log is damaged or has gaps (named: tick, byte offset). An external controller (or, with --component "
      "plant, an external plant) is replayed only by a program named after --, never by the command the log "
      "holds",
      {"lagrange replay runs/rigid_2dof", "lagrange replay runs/rigid_2dof --component plant"});
  cmd->add_option("log", o->log,
                  "A run's output directory (its run.lcm) or an LCM log (run.lcm, a stock lcm-logger's)")
      ->required()
      ->check(CLI::ExistingPath);
  o->component_option =
      cmd->add_option(
             "--component", o->component,
             "Component to replay: controller (default; CONTROL_COMMAND), actuator (ACTUATOR_STATE) or "
             "plant (PLANT_TRUTH, PLANT_POSITION, PLANT_MOTOR, PLANT_RATE). By default, a log whose "
             "controller is external and no command after --: the actuator and the plant")
          ->check(CLI::IsMember({"controller", "actuator", "plant"}));
  cmd->add_option("--set", o->overrides,
                  "Override a key of the logged scenario before replaying (e.g. to check that a "
                  "changed gain is caught); repeatable");
  cmd->add_option("command", o->external_command,
                  "After --: the program (and its arguments) that replays the log's external controller "
                  "(or with --component plant its external plant), "
                  "started in the current directory in a private network namespace. The command the log "
                  "holds is shown, never run");
  return {cmd, [o](const Invocation& inv) {
            // A run's folder stands for its log, as report, export and view take it.
            ReplayCommandLine line = *o;
            std::error_code not_a_directory;
            if (std::filesystem::is_directory(line.log, not_a_directory))
              line.log = (std::filesystem::path(line.log) / "run.lcm").string();
            return replay(line, inv.argv);
          }};
}

}  // namespace lagrange::tools
