/// @file
/// `lagrange run`'s command line (tools/run/run_command.hpp).
#include <CLI/CLI.hpp>
#include <memory>

#include "tools/run/run_command.hpp"

namespace lagrange::tools {

namespace {
struct RunCommandLine {
  RunOptions run;
  std::string mode;
  bool no_netns = false;
};
}  // namespace

Subcommand addRunCommand(CLI::App& app) {
  auto o = std::make_shared<RunCommandLine>();
  RunOptions& run = o->run;
  CLI::App* cmd =
      app.add_subcommand("run", "Run a scenario: plant, actuator, controller and logger as LCM processes");
  cmd->add_option("config", run.config_path, "Scenario YAML file, e.g. configs/rigid_2dof.yaml")->required();
  cmd->add_option("-o,--out", run.out_dir, "Output directory (created if missing)")->required();
  cmd->add_option(
      "--set", run.overrides,
      "Override a config key: key=value, value in YAML (e.g. controller.kp=[100,20]); repeatable");
  cmd->add_option("--mode", o->mode,
                  "Override the scenario's mode: lockstep (processes over LCM, deterministic), realtime "
                  "(processes over LCM, each on its own fixed-rate loop) or inproc (the same cores in one "
                  "process, no LCM)")
      ->check(CLI::IsMember({"lockstep", "realtime", "inproc"}));
  cmd->add_flag("--no-netns", o->no_netns,
                "Use the machine's network instead of a private network namespace "
                "(LCM traffic then reaches other processes on this host)");
  cmd->add_option("--lcm-url", run.lcm_url, "LCM URL for the run (default: a fresh udpm port, TTL 0)");
  cmd->add_flag("--strict", run.strict,
                "Refuse to run when an evaluated gain condition (eq. 11; eq. 632 for m = 1) is violated");
  cmd->add_flag(
      "--check-sampled", run.check_sampled,
      "Before the run, simulate the sampled loop as configured against the same loop at a fine rate "
      "(as lagrange check-gains; seconds) and print its verdict; with --strict, refuse when it "
      "DIVERGES. summary.json gains.sampled_simulation keeps it");
  cmd->add_flag("-q,--quiet", run.quiet, "Print errors only");
  cmd->add_option("--run-id", run.run_id,
                  "The run's identity stamped on every message (default: random; with --processes, derived "
                  "from the LCM URL and the scenario so every host agrees)");
  cmd->add_option("--processes", run.processes,
                  "Start only these processes here (comma-separated: logger, controller, actuator, plant), "
                  "for a run spread over several hosts; needs --no-netns and --lcm-url")
      ->delimiter(',');
  cmd->add_option("--key-file", run.key_file,
                  "The run's secret key (from `lagrange keygen`, mode 600) instead of a fresh one in "
                  "OUT/run.key; every host of a run spread with --processes needs the same one")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--check", run.check,
                "Exit 3, naming the metric and its value, when the run completes but misses its stated "
                "metric (summary.json tracking.met false): for guarding a controller in CI");
  cmd->add_flag("--report", run.report,
                "At the end of the run, write CSV files and PNG plots to OUT/report (as lagrange report)");
  return {cmd, [o](const Invocation& inv) {
            RunOptions options = o->run;
            options.private_netns = !o->no_netns;
            if (!o->mode.empty()) options.overrides.push_back("mode=" + o->mode);
            options.self_argv = inv.argv;
            options.sign = inv.sign;
            return runScenario(options);
          }};
}

}  // namespace lagrange::tools
