/// @file
/// `lagrange`: the front end users type. Subcommands:
///   run           launch a scenario (plant, actuator, controller, logger over LCM)
///   check-gains   print the gain conditions of a scenario without running it
///   compare       run a scenario for several controllers and tabulate them
///   sweep         many in-process runs over axes of scenario keys (locally or on Slurm)
///   keygen        write a secret key for a run spread over hosts
///   replay, report, spy, view

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "controller/gain_suggestion.hpp"
#include "runtime/key_file.hpp"
#include "tools/command_error.hpp"
#include "tools/compare.hpp"
#include "tools/netns.hpp"
#include "tools/replay.hpp"
#include "tools/replay_external.hpp"
#include "tools/report.hpp"
#include "tools/run_command.hpp"
#include "tools/spy.hpp"
#include "tools/sweep.hpp"
#include "tools/view.hpp"
#include "util/error.hpp"

namespace lagrange {
namespace {

int checkGains(const std::string& path, const std::vector<std::string>& overrides, bool suggest) {
  try {
    const config::Scenario s = config::loadScenario(path, overrides);
    const controller::GainReport r = controller::checkGains(s);
    std::cout << controller::describe(r) << "\n";
    // Exit 1 when the theory's conditions fail, or when the sampled loop at the
    // configured rate is unstable near the reference ("slow" only warns).
    if (!suggest) return r.holds() && r.sampled.verdict != "unstable" ? 0 : 1;
    if (r.unchecked) {
      std::cout << "\nno suggestion: --suggest knows the paper's controllers only\n";
      return kExitFailed;
    }
    config::Scenario suggested;
    try {
      suggested = controller::suggestGains(s);
    } catch (const std::range_error& e) {
      std::cout << "\nno suggestion: " << e.what() << "\n";
      return kExitFailed;
    }
    const controller::GainReport check = controller::checkGains(suggested);
    std::cout << "\nsuggested gains (the paper's constructive rules; other keys unchanged):\n"
              << controller::controllerYaml(suggested) << "\nwith them:\n"
              << controller::describe(check) << "\n";
    return check.holds() ? 0 : 1;
  } catch (const config::ConfigError& e) {
    return tools::failWith("lagrange check-gains", e);
  } catch (const std::exception& e) {
    return tools::failWith("lagrange check-gains: cannot evaluate the gain conditions", e);
  }
}

int replay(const std::string& log_path, const std::string& component,
           const std::vector<std::string>& overrides, const std::vector<std::string>& self_argv) {
  // An external controller is replayed by running it again, on a bus of its
  // own: in a private network namespace, as `lagrange run` does.
  if (component == "controller" && !tools::insidePrivateNetns() && tools::isExternalControllerLog(log_path)) {
    const std::string why = tools::reexecInPrivateNetns(self_argv);  // returns only on failure
    std::cerr << "lagrange replay: " << why << "; install util-linux to replay an external controller\n";
    return kExitFailed;
  }
  try {
    const tools::ReplayResult r = component == "actuator" ? tools::replayActuator(log_path, overrides)
                                  : component == "plant"  ? tools::replayPlant(log_path, overrides)
                                                          : tools::replayController(log_path, overrides);
    for (const auto& w : r.warnings) std::cerr << "lagrange replay: warning: " << w << "\n";
    if (r.divergence) {
      std::cout << "lagrange replay: " << component << " DIVERGED after " << r.commands << " outputs at "
                << *r.divergence << "\n";
      return kExitFailed;
    }
    std::cout << "lagrange replay: " << component << " reproduced all " << r.commands
              << " recorded outputs bit for bit (" << r.events << " events read)\n";
    return kExitOk;
  } catch (const tools::ReplayError& e) {
    for (const auto& w : e.warnings()) std::cerr << "lagrange replay: warning: " << w << "\n";
    return tools::failWith("lagrange replay", e);
  } catch (const std::exception& e) {
    return tools::failWith("lagrange replay", e);
  }
}

int report(const std::string& target, std::string out_dir) {
  namespace fs = std::filesystem;
  const std::string log_path = fs::is_directory(target) ? (fs::path(target) / "run.lcm").string() : target;
  if (out_dir.empty()) out_dir = (fs::path(log_path).parent_path() / "report").string();
  try {
    tools::printReport(tools::writeReport(log_path, out_dir), out_dir, "lagrange report: ");
    return kExitOk;
  } catch (const std::exception& e) {
    return tools::failWith("lagrange report", e);
  }
}

int DoMain(int argc, char** argv) {
  CLI::App app{"lagrange: observer-less output-feedback tracking control testbed (LCM + ODE)", "lagrange"};
  app.require_subcommand(1);

  tools::RunOptions run;
  bool no_netns = false;
  CLI::App* run_cmd =
      app.add_subcommand("run", "Run a scenario: plant, actuator, controller and logger as LCM processes");
  run_cmd->add_option("config", run.config_path, "Scenario YAML file, e.g. configs/rigid_2dof.yaml")
      ->required();
  run_cmd->add_option("-o,--out", run.out_dir, "Output directory (created if missing)")->required();
  run_cmd->add_option(
      "--set", run.overrides,
      "Override a config key: key=value, value in YAML (e.g. controller.kp=[100,20]); repeatable");
  std::string mode;
  run_cmd
      ->add_option("--mode", mode,
                   "Override the scenario's mode: lockstep (processes over LCM, deterministic), realtime "
                   "(processes over LCM, each on its own fixed-rate loop) or inproc (the same cores in one "
                   "process, no LCM)")
      ->check(CLI::IsMember({"lockstep", "realtime", "inproc"}));
  run_cmd->add_flag("--no-netns", no_netns,
                    "Use the machine's network instead of a private network namespace "
                    "(LCM traffic then reaches other processes on this host)");
  run_cmd->add_option("--lcm-url", run.lcm_url, "LCM URL for the run (default: a fresh udpm port, TTL 0)");
  run_cmd->add_flag("--strict", run.strict,
                    "Refuse to run when an evaluated gain condition (eq. 11; eq. 632 for m = 1) is violated");
  run_cmd->add_flag("-q,--quiet", run.quiet, "Print errors only");
  run_cmd->add_option(
      "--run-id", run.run_id,
      "The run's identity stamped on every message (default: random; with --processes, derived "
      "from the LCM URL and the scenario so every host agrees)");
  run_cmd
      ->add_option("--processes", run.processes,
                   "Start only these processes here (comma-separated: logger, controller, actuator, plant), "
                   "for a run spread over several hosts; needs --no-netns and --lcm-url")
      ->delimiter(',');
  run_cmd
      ->add_option("--key-file", run.key_file,
                   "The run's secret key (from `lagrange keygen`, mode 600) instead of a fresh one in "
                   "OUT/run.key; every host of a run spread with --processes needs the same one")
      ->check(CLI::ExistingFile);
  run_cmd->add_flag("--check", run.check,
                    "Exit 3, naming the metric and its value, when the run completes but misses its stated "
                    "metric (summary.json tracking.met false): for guarding a controller in CI");
  run_cmd->add_flag(
      "--report", run.report,
      "At the end of the run, write CSV files and PNG plots to OUT/report (as lagrange report)");

  std::string gains_config;
  std::vector<std::string> gains_overrides;
  CLI::App* gains_cmd = app.add_subcommand(
      "check-gains",
      "Print the gain conditions of a scenario (k_c, k_delta, eq. 11; "
      "eta and eq. 632 for m = 1; Theorem 3 and Proposition 1 "
      "for m >= 2) and whether the sampled implementation at the configured rate is adequate, "
      "without running it; exit 1 if a condition is violated or the "
      "sampled loop is unstable");
  gains_cmd->add_option("config", gains_config, "Scenario YAML file")->required();
  gains_cmd->add_option("--set", gains_overrides, "Override a config key: key=value; repeatable");
  bool suggest = false;
  gains_cmd->add_flag(
      "--suggest", suggest,
      "Also propose gains that satisfy the conditions (eq. 11; lego/632a, 794, 795 for chains) "
      "and check them; exit 0 if the suggestion passes");

  std::string replay_log, component = "controller";
  std::vector<std::string> replay_overrides;
  CLI::App* replay_cmd = app.add_subcommand(
      "replay",
      "Feed a component's recorded inputs from an LCM log into its core and compare every output with the "
      "recorded one; print the first divergence (tick, time, field, both values); exit 1 on any");
  replay_cmd->add_option("log", replay_log, "LCM log written by lagrange run (run.lcm)")
      ->required()
      ->check(CLI::ExistingFile);
  replay_cmd
      ->add_option("--component", component,
                   "Component to replay: controller (default; CONTROL_COMMAND), actuator (ACTUATOR_STATE) or "
                   "plant (PLANT_TRUTH, PLANT_POSITION, PLANT_MOTOR, PLANT_RATE)")
      ->check(CLI::IsMember({"controller", "actuator", "plant"}));
  replay_cmd->add_option("--set", replay_overrides,
                         "Override a key of the logged scenario before replaying (e.g. to check that a "
                         "changed gain is caught); repeatable");

  std::string report_target, report_out;
  CLI::App* report_cmd = app.add_subcommand(
      "report",
      "Write one CSV file per channel of a run's log (rows: first copy of each tick; columns: the "
      "message fields per joint) and PNG plots drawn by gnuplot (tracking error, joints, torques, filter, "
      "actuator and, for realtime runs, timing histograms)");
  report_cmd->add_option("target", report_target, "A run directory (its run.lcm) or an LCM log file")
      ->required()
      ->check(CLI::ExistingPath);
  report_cmd->add_option(
      "-o,--out", report_out,
      "Directory for the CSV files, plots and plots.gp (default: report/ next to the log)");

  tools::CompareOptions compare;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare",
      "Run one scenario for several controllers (in-process, several at a time), each tuned by its section "
      "compare.controllers.TYPE; write a table (Markdown and CSV: convergence time, final and RMS error, max "
      "torque, torque total variation, control energy), overlay plots of the error and the torques, and with "
      "--sweep the steady-state error against one key (docs/comparison.md)");
  compare_cmd
      ->add_option("config", compare.config_path, "Scenario YAML file, e.g. configs/compare_pelican.yaml")
      ->required()
      ->check(CLI::ExistingFile);
  compare_cmd->add_option("-o,--out", compare.out_dir, "Output directory (created if missing)")->required();
  compare_cmd
      ->add_option("--controllers", compare.controllers,
                   "Controller types to compare, comma-separated (default: every one in compare.controllers)")
      ->delimiter(',');
  compare_cmd->add_option("--set", compare.overrides,
                          "Override a config key in every run (after the controller's section): key=value; "
                          "repeatable");
  compare_cmd->add_option(
      "--sweep", compare.sweep,
      "Also run each controller for every value of one key, KEY=[V1, V2, ...] (a YAML list), "
      "e.g. 'sensors.position.counts_per_revolution=[4096, 65536]' (default: compare.sweep)");
  compare_cmd->add_option("-j,--jobs", compare.jobs, "Runs at a time (default: one per core)")
      ->check(CLI::NonNegativeNumber);
  compare_cmd->add_flag("-q,--quiet", compare.quiet, "Print errors only");

  tools::SweepOptions sweep;
  CLI::App* sweep_cmd = app.add_subcommand(
      "sweep",
      "Run a scenario many times in-process over axes of its keys (lists, linear and log ranges, initial "
      "errors by norm and random direction; grids, seeded random or Halton samples), on every core or as a "
      "Slurm job array; write one row per run (parameters, convergence time, final and max error, diverged, "
      "the gain verdicts, wall time) to OUT/sweep.csv and OUT/sweep.jsonl, and maps as PNGs. Resumable: run "
      "the same command again after a stop (docs/sweeps.md)");
  sweep_cmd->add_option("sweep_file", sweep.sweep_file, "Sweep YAML file, e.g. sweeps/rigid_rates.yaml")
      ->check(CLI::ExistingFile);
  sweep_cmd->add_option("-o,--out", sweep.out_dir,
                        "Output directory (created if missing; resumed if it holds this sweep)");
  sweep_cmd->add_option("-j,--jobs", sweep.jobs, "Local runs at a time (default: one per core)")
      ->check(CLI::NonNegativeNumber);
  sweep_cmd->add_flag("-q,--quiet", sweep.quiet, "Print errors only");
  sweep_cmd->add_flag(
      "--dry-run", sweep.dry_run,
      "Plan the sweep and check every run's scenario, print how many runs it has; run nothing");
  sweep_cmd->add_flag(
      "--slurm", sweep.slurm,
      "Submit the runs as a Slurm job array (sbatch) instead of running them here; OUT must be on "
      "a directory every node shares, and this binary on every node at the same path");
  sweep_cmd->add_flag("--no-wait", sweep.no_wait,
                      "--slurm: return once the job is submitted; then `lagrange sweep collect OUT`");
  sweep_cmd->add_option("--shards", sweep.shards, "--slurm: array tasks (default: min(runs to do, 64))")
      ->check(CLI::PositiveNumber);
  sweep_cmd->add_option("--partition", sweep.partition, "--slurm: sbatch --partition");
  sweep_cmd->add_option("--time", sweep.time_limit, "--slurm: sbatch --time, each array task's limit");
  sweep_cmd->add_option("--account", sweep.account, "--slurm: sbatch --account");
  sweep_cmd->add_option("--sbatch-arg", sweep.sbatch_args,
                        "--slurm: one more sbatch option as it is, e.g. --sbatch-arg=--qos=long; repeatable");
  std::string collect_dir;
  bool collect_quiet = false;
  CLI::App* collect_cmd = sweep_cmd->add_subcommand(
      "collect",
      "Merge the rows a sweep's shards wrote (a Slurm sweep run with --no-wait, or a stopped one) into "
      "OUT/sweep.csv, OUT/sweep.jsonl and the maps; exit 1 if rows are missing");
  collect_cmd->add_option("out", collect_dir, "The sweep's output directory")
      ->required()
      ->check(CLI::ExistingDirectory);
  collect_cmd->add_flag("-q,--quiet", collect_quiet, "Print errors only");

  std::string shard_dir;
  int shard = -1, shard_of = 0, shard_parent = 0;
  CLI::App* shard_cmd =
      app.add_subcommand("sweep-shard", "One shard of a sweep (what lagrange sweep starts)");
  shard_cmd->group("");  // internal: not listed in --help
  shard_cmd->add_option("out", shard_dir, "The sweep's output directory")->required();
  shard_cmd->add_option("--shard", shard, "This shard, K in 0..N-1")->required();
  shard_cmd->add_option("--of", shard_of, "Shards, N")->required();
  shard_cmd->add_option("--parent", shard_parent, "The local sweep's pid: stop when it ends");

  std::string keygen_file;
  CLI::App* keygen_cmd = app.add_subcommand(
      "keygen",
      "Write a fresh secret key (64 hex digits, mode 600) for runs spread over hosts: give the same file to "
      "each host's `lagrange run --processes ... --key-file FILE`");
  keygen_cmd->add_option("file", keygen_file, "The key file to create (never overwritten)")->required();

  tools::SpyOptions spy;
  CLI::App* spy_cmd = app.add_subcommand(
      "spy",
      "Start lcm-spy with this project's message types on a running scenario's LCM URL (joining its private "
      "network namespace), so every channel is decoded; needs a display");
  spy_cmd->add_option("run", spy.run_dir, "Output directory of a running `lagrange run` (it holds lcm.json)")
      ->check(CLI::ExistingDirectory);
  spy_cmd->add_option("--lcm-url", spy.lcm_url,
                      "LCM URL to watch (default: the run's; without a run, LCM's default URL)");
  spy_cmd->add_flag("--print-command", spy.print_only, "Print the java command line instead of running it");

  tools::ViewOptions view;
  CLI::App* view_cmd = app.add_subcommand(
      "view",
      "Draw the arm in a web browser: from a log (play, pause, speed, seek) or live from a running scenario "
      "(joining its private network namespace); prints the page's URL");
  view_cmd->add_option("source", view.source,
                       "A run's output directory (live while the run goes, else its run.lcm) or a log file");
  view_cmd->add_option("--host", view.host,
                       "Address to listen on (default 127.0.0.1; others need --allow-remote)");
  view_cmd->add_option("--port", view.port, "Port to listen on (default 8642; 0: any free port)");
  view_cmd->add_flag(
      "--allow-remote", view.allow_remote,
      "Allow a --host that is not loopback: anyone who reaches it sees the run (no authentication)");
  view_cmd->add_option(
      "--lcm-url", view.lcm_url,
      "View live traffic on this LCM URL (default: the running scenario's, from its lcm.json)");
  view_cmd->add_option("--key-file", view.key_file,
                       "Live: the run's secret key, so that only what its processes sent is drawn (default: "
                       "the running scenario's run.key)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every other parse error is bad input (CLI11's own codes are 100+).
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  if (*run_cmd) {
    run.private_netns = !no_netns;
    if (!mode.empty()) run.overrides.push_back("mode=" + mode);
    run.self_argv.assign(argv, argv + argc);
#ifdef LAGRANGE_BENCH_UNSIGNED
    run.sign = false;
#endif
    run.self_argv[0] = std::filesystem::read_symlink("/proc/self/exe").string();
    return tools::runScenario(run);
  }
  if (*keygen_cmd) {
    try {
      runtime::writeKeyFile(keygen_file, transport::randomMessageKey());
      return kExitOk;
    } catch (const std::exception& e) {
      return tools::failWith("lagrange keygen", e);
    }
  }
  if (*compare_cmd) {
    compare.self_exe = std::filesystem::read_symlink("/proc/self/exe").string();
    return tools::runComparison(compare);
  }
  if (*sweep_cmd) {
    if (*collect_cmd) return tools::collectSweep(collect_dir, collect_quiet);
    if (sweep.sweep_file.empty() || (sweep.out_dir.empty() && !sweep.dry_run)) {
      std::cerr << "lagrange sweep: expected a sweep file and --out DIR (or: lagrange sweep collect DIR)\n";
      return kExitBadInput;
    }
    sweep.self_exe = std::filesystem::read_symlink("/proc/self/exe").string();
    return tools::runSweep(sweep);
  }
  if (*shard_cmd) return tools::runSweepShard(shard_dir, shard, shard_of, shard_parent);
  if (*replay_cmd) {
    std::vector<std::string> self(argv, argv + argc);
    self[0] = std::filesystem::read_symlink("/proc/self/exe").string();
    return replay(replay_log, component, replay_overrides, self);
  }
  if (*report_cmd) return report(report_target, report_out);
  if (*spy_cmd) return tools::runSpy(spy);
  if (*view_cmd) return tools::runView(view);
  return checkGains(gains_config, gains_overrides, suggest);
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
