/// @file
/// `lagrange run`'s command line (tools/run/run_command.hpp).
#include <CLI/CLI.hpp>
#include <memory>
#include <sstream>

#include "tools/command_error.hpp"
#include "tools/run/run_command.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

namespace {
struct RunCommandLine {
  RunOptions run;
  std::string mode;
  bool no_netns = false;
  CLI::Option* check_option = nullptr;
};

// `lagrange run --check SCENARIO.yaml -o OUT`: --check's value is optional,
// so the parser gave it the scenario's path. A value ending in .yaml or .yml
// is no check (those are `met` or KEY OP NUMBER): it is the scenario (a
// missing file is then named as such), and that --check stands alone (the
// stated metric).
bool scenarioFromCheck(RunOptions& options) {
  for (std::string& value : options.checks) {
    const auto endsWith = [&value](const std::string& suffix) {
      return value.size() > suffix.size() &&
             value.compare(value.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    if (!endsWith(".yaml") && !endsWith(".yml")) continue;
    options.config_path = value;
    value.clear();
    return true;
  }
  return false;
}

// The usage line shows SCENARIO without brackets: it is required, though
// optional to the parser (addRunCommand says why).
class RunUsage : public CLI::Formatter {
 public:
  std::string make_option_usage(const CLI::Option* opt) const override {
    const std::string usage = CLI::Formatter::make_option_usage(opt);
    const bool bracketed = usage.size() > 2 && usage.front() == '[' && usage.back() == ']';
    return opt->get_name(true) == "SCENARIO" && bracketed ? usage.substr(1, usage.size() - 2) : usage;
  }
};
}  // namespace

Subcommand addRunCommand(CLI::App& app) {
  auto o = std::make_shared<RunCommandLine>();
  RunOptions& run = o->run;
  CLI::App* cmd = app.add_subcommand("run", "Run a scenario: its four processes over LCM");
  describeCommand(
      *cmd,
      "Start the plant, actuator, controller and logger of a scenario as processes over LCM, in a private "
      "network namespace (mode lockstep or realtime; mode inproc runs them in this process), with "
      "the run's own key; show the progress; write run.lcm, summary.json and each process's log "
      "to OUT; print the result. Exit 0 when the run completed, 1 when it failed (a process "
      "died or stopped it), 2 on bad input, 3 when --check misses, 130 when interrupted "
      "(docs/reliability.md, \"Errors and exit codes\"; the run's status: docs/summary.md)",
      {"lagrange run configs/rigid_2dof.yaml --out runs/rigid_2dof",
       "lagrange run configs/rigid_2dof.yaml --out runs/fast --mode inproc --set 'controller.kp=[200,12]'"});
  // Not ->required(): `--check SCENARIO.yaml` hands the path to --check,
  // whose value is optional; the callback takes it back (scenarioFromCheck).
  // Required, though optional to the parser: a `--check` that swallowed the
  // scenario hands it back (scenarioFromCheck), and its absence is named then.
  cmd->formatter(std::make_shared<RunUsage>());
  cmd->add_option("SCENARIO", run.config_path, "Scenario YAML file, e.g. configs/rigid_2dof.yaml (required)")
      ->type_name("");
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
  cmd->add_flag(
      "--strict", run.strict,
      "Refuse to run when an evaluated gain condition (eq. (12); eqs. (56a)-(56c) for m = 1) is violated");
  cmd->add_flag(
      "--check-sampled", run.check_sampled,
      "Before the run, simulate the sampled loop as configured against the same loop at a fine rate "
      "(as lagrange check-gains; seconds) and print its verdict; with --strict, refuse when it "
      "is UNSTABLE about the reference or DIVERGES. summary.json gains.sampled_simulation keeps it");
  cmd->add_flag("-q,--quiet", run.quiet, "Print errors only");
  cmd->add_option("--run-id", run.run_id,
                  "The run's identity stamped on every message (default: random; with --processes, derived "
                  "from the value the hosts' launchers agree on before the run)");
  cmd->add_option("--processes", run.processes,
                  "Start only these processes here (comma-separated: logger, controller, actuator, plant), "
                  "for a run spread over several hosts; needs --no-netns and --lcm-url")
      ->delimiter(',');
  cmd->add_option("--key-file", run.key_file,
                  "A secret key shared by runs or hosts (from `lagrange keygen`, mode 600): the run's key, "
                  "in OUT/run.key, is derived from it and a value fresh for this run, so no run accepts "
                  "another's traffic; every host of a run spread with --processes needs the same one")
      ->check(CLI::ExistingFile);
  cmd->add_option("--join-timeout", run.join_timeout,
                  "With --processes: seconds this host's launcher waits for the other hosts' launchers to "
                  "agree on the run before it gives up (exit 1); 1 to 86400")
      ->capture_default_str()
      ->type_name("SECONDS")
      ->check(CLI::Range(1.0, 86400.0).description(""));
  CLI::Option* check =
      cmd->add_option(
             "--check", run.checks,
             "Exit 3, naming each one missed with its value, when the run completes but misses a "
             "check: alone, the scenario's stated metric (summary.json tracking.met; a miss names the "
             "verdict's reasons); or a comma-separated list of met, no_warnings (the verdict warns of "
             "nothing) and KEY OP NUMBER (OP one of < <= > >=, KEY a number of "
             "summary.json or final_error, max_error, convergence_time, rms_last_second, "
             "max_torque), e.g. --check 'met,final_error<1e-4,max_torque<=300'; repeatable")
          ->expected(0, 1)
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  o->check_option = check;
  cmd->add_option(
      "--junit", run.junit_path,
      "Write the checks' results (--check's, or the stated metric's) as JUnit XML to FILE, for CI "
      "systems");
  cmd->add_flag("--share", run.share,
                "Create the run's folder and files as your umask allows (default: the folder 0700 and its "
                "files 0600: a run's log, key and summary are yours alone)");
  cmd->add_flag("--report", run.report,
                "At the end of the run, write CSV files and PNG plots to OUT/report (as lagrange report)");
  return {cmd, [o](const Invocation& inv) {
            RunOptions options = o->run;
            if (options.config_path.empty() && !scenarioFromCheck(options))
              return failWith("lagrange run",
                              BadInput("no scenario given; expected `lagrange run SCENARIO.yaml -o OUT "
                                       "[OPTIONS]`, e.g. lagrange run configs/rigid_2dof.yaml -o out"));
            options.private_netns = !o->no_netns;
            // Each --check's comma-separated list; --check alone stores an empty value.
            std::vector<std::string> checks;
            for (const std::string& list : options.checks) {
              std::stringstream items(list);
              for (std::string item; std::getline(items, item, ',');)
                if (!item.empty()) checks.push_back(item);
            }
            options.checks = checks;
            options.check = o->check_option->count() > 0 || !options.junit_path.empty();
            if (options.check && options.checks.empty()) options.checks = {"met"};
            if (!o->mode.empty()) options.overrides.push_back("mode=" + o->mode);
            options.self_argv = inv.argv;
            options.sign = inv.sign;
            return runScenario(options);
          }};
}

}  // namespace lagrange::tools
