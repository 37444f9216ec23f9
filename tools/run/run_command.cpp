#include "tools/run/run_command.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "config/scenario.hpp"
#include "config/scenario_json.hpp"
#include "controller/gain_report.hpp"
#include "controller/gain_report_json.hpp"
#include "logger/verdict.hpp"
#include "logs/out_dir_lock.hpp"
#include "plant/plant_sim.hpp"
#include "plant/scenario_plant.hpp"
#include "runtime/key_file.hpp"
#include "tools/command_error.hpp"
#include "tools/report/report.hpp"
#include "tools/run/launch_rules.hpp"
#include "tools/run/metric_checks.hpp"
#include "tools/run/progress_reader.hpp"
#include "tools/run/run_key.hpp"
#include "tools/run/run_outcome.hpp"
#include "tools/run/session_handshake.hpp"
#include "tools/spy/spy.hpp"
#include "transport/channels.hpp"
#include "transport/checksum.hpp"
#include "transport/message_auth.hpp"
#include "transport/messages.hpp"
#include "transport/rate_loop.hpp"
#include "transport/run_clock.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "util/terminal_text.hpp"
#include "wiring/inproc_runner.hpp"
#include "wiring/netns.hpp"
#include "wiring/progress.hpp"
#include "wiring/sampled_simulation.hpp"
#include "wiring/supervisor.hpp"

namespace lagrange::tools {

namespace fs = std::filesystem;

namespace {
std::atomic<int> launcher_signal{0};
void onSignal(int sig) { launcher_signal = sig; }

std::string executableDir() { return fs::read_symlink("/proc/self/exe").parent_path().string(); }

// Creates the directory and proves it writable, before anything starts.
std::string prepareOutDir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  const std::string probe = (fs::path(dir) / ".lagrange-write-test").string();
  try {
    if (ec) throw RuntimeFault(ec.message());
    close(util::createOutputFile(probe));  // not through a link planted there
  } catch (const util::UnsafeOutputPath& e) {
    throw config::ConfigError(std::string("output directory: ") + e.what());
  } catch (const std::exception& e) {
    throw config::ConfigError("output directory '" + dir + "' cannot be created or written (" + e.what() +
                              "); expected a writable directory (--out)");
  }
  fs::remove(probe, ec);
  return fs::absolute(dir).string();
}

// Every file a run writes into the output directory, so that a link planted
// in the place of one is refused (exit 2) before anything starts, rather
// than at the moment its writer comes to it. Each writer creates its file
// with util::createOutputFile all the same (a link planted during the run).
void checkOutputPaths(const std::string& out_dir, bool report) {
  for (const char* name :
       {"run.lcm", "summary.json", "config.resolved.yaml", "config.resolved.json", "gains.json", "lcm.json",
        "run.key", "logger.log", "controller.log", "actuator.log", "plant.log"})
    util::checkOutputPath((fs::path(out_dir) / name).string());
  const std::string report_dir = (fs::path(out_dir) / "report").string();
  if (!report || !fs::exists(fs::symlink_status(report_dir))) return;
  util::makeOutputDirectory(report_dir);  // refuses a link or a file named report
  // The report's writers (CSV, plots) replace the files of an earlier report.
  for (const auto& entry : fs::directory_iterator(report_dir)) util::checkOutputPath(entry.path().string());
}

// The gain report; with --check-sampled the sampled loop simulated too
// (before the run's own processes start, so they do not share the cores).
controller::GainReport checkGainsBeforeRun(const config::Scenario& scenario, const RunOptions& opt) {
  controller::GainReport gains = controller::checkGains(scenario);
  if (opt.check_sampled) gains.simulated = wiring::simulateSampledData(scenario);
  return gains;
}

// Prints what the robot's model leaves out of its description (URDF limits,
// damping, lumped branches) and the gain report; false when --strict forbids running.
bool gainsAllowRun(const config::Scenario& scenario, const controller::GainReport& gains,
                   const RunOptions& opt) {
  if (!opt.quiet && scenario.urdf_model)
    for (const std::string& note : scenario.urdf_model->notes())
      std::cout << "robot.urdf: " << util::terminalSafe(note) << "\n";  // joint names from a file
  if (!opt.quiet)
    std::cout << util::terminalSafeLines(controller::describe(gains)) << "\n"
              << (gains.simulated
                      ? ""
                      : "sampled-data check: not simulated before this run (--check-sampled, or "
                        "`lagrange check-gains`, simulates the loop as configured against the same "
                        "loop at a fine rate)\n");
  if (!gains.holds() && opt.strict) {
    std::cerr << "lagrange run: refusing to start (--strict) because the gain condition is "
              << (gains.unchecked ? "not checked" : "violated") << "\n";
    return false;
  }
  if (opt.strict && gains.simulated && gains.simulated->fails()) {
    std::cerr << "lagrange run: refusing to start (--strict) because the sampled loop "
              << (gains.simulated->verdict == "unstable" ? "is unstable about the reference" : "diverges")
              << " in simulation: " << gains.simulated->why << "\n";
    return false;
  }
  return true;
}

std::string writeResolved(const config::Scenario& scenario, const std::string& source,
                          const std::string& out_dir) {
  const std::string path = (fs::path(out_dir) / "config.resolved.yaml").string();
  util::writeOutputFile(path, "# Resolved scenario of this run: defaults, the file " + source +
                                  " and --set overrides.\n" + config::toYaml(scenario));
  // The same as JSON, for programs that read no YAML (an external controller
  // on the standard library only: LAGRANGE_CONFIG_JSON).
  util::writeOutputFile((fs::path(out_dir) / "config.resolved.json").string(), config::toJson(scenario));
  return path;
}

// OUT/gains.json: the check made here, for the controller and the logger to
// read instead of repeating it (controller/gain_report_json.hpp).
std::string writeGains(const config::Scenario& scenario, const controller::GainReport& gains,
                       const std::string& out_dir) {
  const std::string path = (fs::path(out_dir) / "gains.json").string();
  util::writeOutputFile(path, controller::gainReportJson(gains, config::toYaml(scenario)));
  return path;
}

// The logger wrote summary.json before the others were reaped; the launcher
// adds what only it knows: each process's CPU time, the processes that died
// and were restarted (supervision), how an external controller was
// scheduled, and, when it ended the run because a process died, why
// (`failure`). The status then says what happened: `diverged` when the plant
// stopped the simulation (as in process), `failed` for any other death --
// not the `interrupted` the logger wrote when it was stopped, which a sweep
// would run again -- and `completed` stays when every tick was recorded.
// Only the summary of this run (its run_id): a logger that died before
// writing leaves an older run's summary.json in OUT, which is not touched.
void addLauncherFacts(const std::string& out_dir, int64_t run_id, const nlohmann::json& cpu,
                      const nlohmann::json& supervision, const nlohmann::json& failure,
                      const std::string& external_scheduler) {
  const fs::path path = fs::path(out_dir) / "summary.json";
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(std::ifstream(path));
  } catch (const std::exception&) {
    return;  // printResult reports the unreadable summary
  }
  if (!j.is_object() || !j.contains("run_id") || !j["run_id"].is_number_integer() ||
      j["run_id"].get<int64_t>() != run_id)
    return;
  j["timing"]["cpu_seconds"] = cpu;
  j["supervision"] = supervision;
  // The logger timed the external controller's loop from its commands; how
  // it was scheduled only the launcher can see.
  if (!external_scheduler.empty() && j["timing"].contains("loops") &&
      j["timing"]["loops"].contains("controller"))
    j["timing"]["loops"]["controller"]["scheduler"] = external_scheduler;
  if (!failure.is_null()) {
    if (j.value("status", std::string()) != "completed")
      j["status"] = failure.value("diverged", false) ? "diverged" : "failed";
    j["failure"] = failure;
  }
  j["verdict"] = logger::runVerdict(j);                    // decided again with what only the launcher knew
  util::writeOutputFile(path.string(), j.dump(2) + "\n");  // throws naming the file and the error
}

// This run's summary.json (its run_id), or null: none, unreadable, another run's.
nlohmann::json thisRunsSummary(const std::string& out_dir, int64_t run_id) {
  try {
    nlohmann::json j = nlohmann::json::parse(std::ifstream(fs::path(out_dir) / "summary.json"));
    if (j.is_object() && j.value("run_id", int64_t{0}) == run_id) return j;
  } catch (const std::exception&) {
  }
  return nullptr;
}

// Whether this run's summary.json says every tick was recorded.
bool runCompleted(const std::string& out_dir, int64_t run_id) {
  const nlohmann::json j = thisRunsSummary(out_dir, run_id);
  return j.is_object() && j.value("status", "") == "completed";
}

// The last `lines` lines of a process's log.
std::vector<std::string> logTail(const std::string& path, int lines) {
  std::ifstream in(path);
  std::vector<std::string> all;
  for (std::string l; std::getline(in, l);) all.push_back(l);
  const size_t from = all.size() > static_cast<size_t>(lines) ? all.size() - lines : 0;
  return {all.begin() + static_cast<std::ptrdiff_t>(from), all.end()};
}

// summary.json's `failure`: a process's end, with the last 5 lines of its
// log each cut at 1000 bytes (a program from outside may write anything);
// for the plant that stopped the simulation (plant::PlantStopped: it
// diverged, or crossed plant.max_rate), `diverged` and the plant's reason.
nlohmann::json failureRecord(const std::string& process, const std::string& how, const std::string& log,
                             const std::vector<std::string>& tail) {
  std::vector<std::string> last;
  for (size_t i = tail.size() > 5 ? tail.size() - 5 : 0; i < tail.size(); ++i)
    last.push_back(tail[i].size() > 1000 ? tail[i].substr(0, 1000) + "..." : tail[i]);
  nlohmann::json f = {{"process", process}, {"how", how}, {"log", log}, {"last_lines", last}};
  if (process == "plant")
    for (auto line = tail.rbegin(); line != tail.rend(); ++line)
      for (const char* mark : plant::kPlantStoppedMarks)
        if (const size_t at = line->find(mark); at != std::string::npos) {
          f["diverged"] = true;
          f["reason"] = line->substr(at, 1000);
          return f;
        }
  return f;
}

void printResult(const std::string& out_dir) {
  std::ifstream in(fs::path(out_dir) / "summary.json");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception&) {
    std::cout << "summary.json could not be read in " << out_dir << "\n";
    return;
  }
  std::cout << resultText(j) << std::flush;
  std::string files;
  for (const auto& entry : fs::directory_iterator(out_dir))
    files += (files.empty() ? "" : ", ") + entry.path().filename().string();
  std::printf("outputs in %s: %s\n", out_dir.c_str(), util::terminalSafe(files).c_str());
}

// --check: a completed run that missed its stated metric exits kExitMetricMissed,
// naming each metric it missed with its value, so CI can guard a controller.
int checkMetric(const RunOptions& opt, const std::string& out_dir, int exit_code) {
  if (!opt.check || exit_code == kExitInterrupted) return exit_code;
  nlohmann::json j;  // null when unreadable: every check then fails, saying why
  try {
    j = nlohmann::json::parse(std::ifstream(fs::path(out_dir) / "summary.json"));
  } catch (const std::exception&) {
  }
  std::vector<MetricCheck> checks;
  for (const std::string& text : opt.checks)
    checks.push_back(parseMetricCheck(text));  // parsed before the run
  const std::vector<CheckResult> results = evaluateChecks(checks, j);
  if (!opt.junit_path.empty()) {
    const double wall = j.is_object() ? j.value("/timing/wall_time"_json_pointer, 0.0) : 0.0;
    try {
      util::writeOutputFile(
          opt.junit_path,
          junitXml(j.is_object() ? j.value("scenario", std::string("?")) : "?", results, wall));
    } catch (const std::exception& e) {
      std::cerr << "lagrange run: --junit " << opt.junit_path << ": " << e.what() << "\n";
      if (exit_code == kExitOk) exit_code = kExitFailed;
    }
  }
  if (exit_code != kExitOk) return exit_code;  // the run's own failure first
  int missed = 0;
  for (const CheckResult& r : results)
    if (!r.passed) {
      ++missed;
      std::cerr << "lagrange run: --check: " << (r.check.key == "met" ? "" : "metric MISSED: ")
                << util::terminalSafeLines(r.message) << "\n";
    }
  return missed > 0 ? kExitMetricMissed : kExitOk;
}

// --report: CSV and plots of the log in OUT/report; a failed or diverged run
// is reported too (its plots show what went wrong). Never changes the exit code.
void writeRunReport(const RunOptions& opt, const std::string& out_dir) {
  if (!opt.report || !runsHere(opt, "logger")) return;
  const std::string report_dir = (fs::path(out_dir) / "report").string();
  try {
    util::makeOutputDirectory(report_dir);  // never into a link planted during the run
    const Report report = writeReport((fs::path(out_dir) / "run.lcm").string(), report_dir);
    if (opt.quiet) {
      for (const auto& w : report.warnings)
        std::cerr << "lagrange run: report: warning: " << util::terminalSafeLines(w) << "\n";
    } else {
      std::cout << "report: "
                << report.csv.rows.size() + (report.timing_rows > 0 ? 1 : 0) +
                       (report.tracking_rows > 0 ? 1 : 0)
                << " CSV files, " << report.plots.written.size() << " plots in " << report_dir << "\n";
      for (const auto& w : report.warnings)
        std::cerr << "lagrange run: report: warning: " << util::terminalSafeLines(w) << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "lagrange run: report: " << util::terminalSafeLines(e.what()) << "\n";
  }
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A run spread over hosts: this launcher starts part of it.
bool partialLaunch(const RunOptions& opt) {
  return !opt.processes.empty() && opt.processes.size() != kProcesses.size();
}

// The run's key and identity, decided before any process starts.
struct RunIdentity {
  transport::MessageKey key{};  ///< meaningless when unsigned
  int64_t run_id = 0;
  std::vector<std::string> members;  ///< the other hosts' launchers (--processes)
};

// The key and run id of this run (docs/reliability.md "Threat model"):
// - no --key-file: a fresh random key; the run id random (or --run-id);
// - --key-file on one host: a key derived from it and 32 fresh random bytes;
// - --processes: the launchers agree on a fresh value over the URL first
//   (tools/run/session_handshake.hpp) and derive the key from it; the run id
//   from it too, unless --run-id. Unsigned (the bench's build of the front
//   end): the run id as before, derived from URL and scenario on several hosts.
// Nothing when Ctrl-C came during the agreement.
std::optional<RunIdentity> decideIdentity(const RunOptions& opt, const std::string& url,
                                          const std::string& resolved_path) {
  RunIdentity id;
  const std::string resolved_text = readText(resolved_path);
  if (!opt.sign) {
    id.run_id = opt.run_id           ? *opt.run_id
                : partialLaunch(opt) ? sharedRunId(url, resolved_text)
                                     : wiring::randomRunId();
    return id;
  }
  if (opt.key_file.empty()) {
    id.key = transport::randomMessageKey();
    id.run_id = opt.run_id ? *opt.run_id : wiring::randomRunId();
    return id;
  }
  const transport::MessageKey shared = runtime::readKeyFile(opt.key_file);
  if (!partialLaunch(opt)) {
    id.key = transport::deriveRunKey(shared, transport::randomNonce());
    id.run_id = opt.run_id ? *opt.run_id : wiring::randomRunId();
    return id;
  }
  HandshakeOptions handshake;
  handshake.lcm_url = url;
  // The meeting point is the URL alone: launchers of different scenarios
  // meet too, and refuse each other naming both (the digest differs).
  handshake.meeting_id = opt.run_id ? *opt.run_id : sharedRunId(url, "");
  handshake.processes = opt.processes;
  handshake.scenario_digest = static_cast<int64_t>(
      transport::fnv1a(reinterpret_cast<const uint8_t*>(resolved_text.data()), resolved_text.size()));
  handshake.timeout = opt.join_timeout;
  handshake.quiet = opt.quiet;
  const std::optional<AgreedRun> agreed =
      agreeWithOtherLaunchers(handshake, shared, [] { return launcher_signal != 0; });
  if (!agreed) return std::nullopt;
  id.key = transport::deriveRunKey(shared, agreed->value);
  id.run_id = opt.run_id ? *opt.run_id : runIdFromValue(agreed->value);
  id.members = agreed->members;
  return id;
}

// CPU time of a process, summed over its restarts.
void addCpu(nlohmann::json& cpu, const wiring::ChildExit& e) {
  nlohmann::json& c = cpu[e.name];
  if (!c.is_object()) c = {{"user", 0.0}, {"system", 0.0}};
  c["user"] = c.value("user", 0.0) + e.cpu_user;
  c["system"] = c.value("system", 0.0) + e.cpu_system;
}

// The files the launcher wrote for its processes to read.
struct HandedFiles {
  std::string resolved;  ///< config.resolved.yaml: every process's --config
  std::string gains;     ///< gains.json: the controller's and the logger's --gains
};

// Starts logger, controller, actuator and plant on a fresh LCM URL, shows
// progress, and watches them until all have exited; returns the exit code.
int superviseProcesses(const config::Scenario& scenario, const RunOptions& opt, const std::string& out_dir,
                       const HandedFiles& handed) {
  const std::string& resolved = handed.resolved;
  const std::string url = opt.lcm_url.empty() ? wiring::freshLcmUrl() : opt.lcm_url;
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  std::signal(SIGPIPE, SIG_IGN);
  // The run's secret (docs/reliability.md): the processes get the file's
  // path, never the key itself, and the key ends with the run.
  std::optional<RunKey> key;
  int64_t run_id = 0;
  try {
    const std::optional<RunIdentity> id = decideIdentity(opt, url, resolved);
    if (!id) {
      std::cerr << "lagrange run: interrupted before the launchers agreed; nothing was started\n";
      return kExitInterrupted;
    }
    run_id = id->run_id;
    if (opt.sign) key.emplace(id->key, out_dir);
    if (!opt.quiet && partialLaunch(opt)) {
      std::cout << "lagrange run: the launchers agreed on this run's key and id (" << run_id << "):";
      for (const std::string& m : id->members) std::cout << " " << util::terminalSafe(m) << ";";
      std::cout << " starting " << joinProcesses(opt.processes) << " here\n";
    }
  } catch (const std::exception& e) {
    return failWith("lagrange run", e);
  }
  const std::vector<std::string> key_args =
      key ? std::vector<std::string>{"--key-file", key->path()} : std::vector<std::string>{};
  // Where `lagrange spy OUT` finds this run: its URL and, in a private
  // network namespace, a process (this one) to take the namespace from.
  try {
    writeEndpoint(out_dir,
                  {url, run_id, opt.private_netns ? std::optional<long>(getpid()) : std::nullopt, getpid()});
  } catch (const std::exception& e) {
    return failWith("lagrange run", e);
  }

  // Progress comes from the logger through a pipe (its --progress-fd), not
  // over LCM: a launcher on the LCM URL would receive every message of the
  // run for the sake of one line every 100 ms.
  int progress_pipe[2];
  if (pipe2(progress_pipe, O_CLOEXEC | O_NONBLOCK) != 0) {
    std::cerr << "lagrange run: cannot create a pipe: " << std::strerror(errno) << "\n";
    return kExitFailed;
  }
  wiring::ProgressDisplay progress(scenario.duration, opt.quiet);
  ProgressReader progress_reader(progress_pipe[0]);

  const std::string bin = executableDir();
  // One clock offset for every process of the run here: their publish_utime
  // stamps then differ by the time that passed (transport/run_clock.hpp).
  const std::string clock_offset =
      std::string(transport::kClockOffsetVariable) + "=" + std::to_string(transport::clockOffsetUs());
  wiring::Supervisor supervisor;
  auto spec = [&](const std::string& name, std::vector<std::string> extra) {
    wiring::ChildSpec c;
    c.name = name;
    c.argv = {bin + "/lagrange-" + name, "--config", resolved, "--lcm-url", url, "--run-id",
              std::to_string(run_id)};
    c.argv.insert(c.argv.end(), key_args.begin(), key_args.end());
    c.argv.insert(c.argv.end(), extra.begin(), extra.end());
    c.log_path = (fs::path(out_dir) / (name + ".log")).string();
    c.env = {clock_offset};
    return c;
  };
  // The logger first, so that it records from the first tick; the plant waits
  // for the logger's STATUS before it starts the clock anyway.
  wiring::ChildSpec logger =
      spec("logger", {"--out", out_dir, "--progress-fd", "3", "--gains", handed.gains});
  logger.pass_fd = progress_pipe[1];
  std::vector<std::string> controller_args = {"--gains", handed.gains};
  if (opt.strict) controller_args.push_back("--strict");
  wiring::ChildSpec controller = spec("controller", controller_args);
  // A program from outside the project in the controller's or the plant's
  // place; what it needs to join the run comes in its environment
  // (docs/external_programs.md), the same for both.
  const std::vector<std::string> external_env = {
      clock_offset,
      "LAGRANGE_LCM_URL=" + url,
      "LAGRANGE_RUN_ID=" + std::to_string(run_id),
      "LAGRANGE_KEY_FILE=" + (key ? key->path() : std::string()),
      "LAGRANGE_CONFIG=" + resolved,
      "LAGRANGE_CONFIG_JSON=" + (fs::path(out_dir) / "config.resolved.json").string(),
      "LAGRANGE_JOINTS=" + std::to_string(scenario.dof()),
      "LAGRANGE_MODE=" + std::string(config::toString(scenario.mode))};
  auto external = [&](wiring::ChildSpec& child, const std::vector<std::string>& command,
                      const std::string& working_directory) {
    child.argv = command;
    child.working_directory = working_directory;
    child.env = external_env;
    // In realtime a loop like the built-in ones: SCHED_FIFO and its CPUs,
    // set before its exec (it cannot be trusted to ask for them itself) --
    // one priority below the built-in loops, because it is FIFO from its
    // first instruction: a JVM's or Python's start-up, and every thread it
    // makes (JIT, GC), must never hold off the built-in loops of equal
    // priority, which the built-in processes avoid by entering FIFO only
    // once prepared (runtime/process.hpp).
    if (scenario.mode != config::Mode::kRealtime) return;
    child.fifo_priority = std::max(0, scenario.realtime.priority - 1);
    if (const auto it = scenario.realtime.cpus.find(child.name); it != scenario.realtime.cpus.end()) {
      transport::checkCpus(it->second, "realtime.cpus." + child.name);
      child.cpus = it->second;
    }
  };
  wiring::ChildSpec plant = spec("plant", {});
  try {
    if (scenario.controller.type == "external")
      external(controller, scenario.controller.command, scenario.controller.working_directory);
    if (scenario.plant.external()) external(plant, scenario.plant.command, scenario.plant.working_directory);
  } catch (const std::exception& e) {
    close(progress_pipe[0]);
    close(progress_pipe[1]);
    return failWith("lagrange run", e);  // exit 2 before anything starts
  }
  std::vector<wiring::ChildSpec> specs = {logger, controller, spec("actuator", {}), plant};
  for (const auto& s : specs)
    if (runsHere(opt, s.name)) supervisor.start(s);
  close(progress_pipe[1]);

  int exit_code = kExitOk;
  nlohmann::json cpu = nlohmann::json::object();
  nlohmann::json supervision = supervisionRecord(scenario.supervision);
  nlohmann::json failure;  // why the launcher ended the run, when a process died (summary.json)
  // After the plant has finished, the others get this long to follow (they
  // normally need milliseconds); then they are stopped, so that a lost final
  // STATUS can never hang a run.
  constexpr double kFollowSeconds = 10.0;
  std::optional<std::chrono::steady_clock::time_point> plant_done;
  // How the external controller was scheduled (summary.json
  // timing.loops.controller.scheduler): looked at once it has answered, long
  // after its exec.
  std::string external_scheduler;
  const bool external_loop = scenario.controller.type == "external" &&
                             scenario.mode == config::Mode::kRealtime && runsHere(opt, "controller");
  while (supervisor.anyRunning()) {
    const auto latest = progress_reader.wait(50);
    if (latest) progress.update(latest->first, latest->second);
    if (latest && latest->first > 0.0 && external_loop && external_scheduler.empty())
      if (const pid_t pid = supervisor.pidOf("controller"); pid > 0)
        external_scheduler = wiring::schedulerOf(pid);
    for (const std::string& notice : progress_reader.takeNotices()) {
      progress.finish();  // the line under the bar, which is drawn again below it
      std::cerr << "lagrange run: " << util::terminalSafeLines(notice) << "\n";
    }
    progress.tick();
    if (launcher_signal != 0) {
      progress.finish();
      std::cerr << "lagrange run: interrupted; stopping every process\n";
      supervisor.stopAll(5.0);
      exit_code = kExitInterrupted;
      break;
    }
    if (plant_done &&
        std::chrono::steady_clock::now() - *plant_done > std::chrono::duration<double>(kFollowSeconds)) {
      progress.finish();
      std::cerr << "lagrange run: warning: processes still running " << kFollowSeconds
                << " s after the plant exited (code 0); stopping them\n";
      for (const wiring::ChildExit& e : supervisor.stopAll(5.0)) {
        addCpu(cpu, e);
        if (e.failed() && e.signal != SIGTERM) exit_code = kExitFailed;
      }
      break;
    }
    for (const wiring::ChildExit& e : supervisor.reap()) {
      addCpu(cpu, e);
      if (e.name == "plant" && !e.failed()) plant_done = std::chrono::steady_clock::now();
      if (!e.failed()) continue;
      if (!plant_done && mayRestart(scenario.supervision, supervision, e.name, e.describe())) {
        progress.finish();
        std::cerr << "lagrange run: process '" << e.name << "' " << e.describe()
                  << "; restarting it (restart " << supervision["restarts"][e.name].get<int>()
                  << " of at most " << scenario.supervision.max_restarts << ", supervision.restart)\n";
        supervisor.restart(e.name);
        // The plant's stall deadline starts over with the start-up allowance
        // (runtime::takeResumeNotice): the restarted process loads and checks
        // its gains before it can answer.
        supervisor.signal("plant", SIGCONT);
        continue;
      }
      progress.finish();
      if (e.name == "logger") progress_reader.wait(0);  // its last word, if it said one
      // The plant exited 0 before the run's end, and the logger, which heard
      // it no more, stopped the run: the plant's doing, not the logger's.
      const std::string plant_short =
          e.name == "logger" && plant_done
              ? plantEndedEarly(thisRunsSummary(out_dir, run_id), scenario.lastTick())
              : std::string();
      if (!plant_short.empty()) {
        const std::string log = (fs::path(out_dir) / "plant.log").string();
        const std::string how =
            plant_short + (progress_reader.loggerError().empty()
                               ? std::string()
                               : "; the logger then stopped the run: " + progress_reader.loggerError());
        std::cerr << "lagrange run: the plant " << util::terminalSafeLines(how) << "; stopping the others\n";
        failure = failureRecord("plant", how, log, logTail(log, 15));
      } else if (e.name == "logger" && !progress_reader.loggerError().empty()) {
        // A write error: the log tail would be on the same full disk.
        std::cerr << "lagrange run: the logger stopped the run: "
                  << util::terminalSafeLines(progress_reader.loggerError()) << "; stopping the others\n";
        // Its summary, when it could write one (a plant gone silent), says why.
        failure = {{"process", "logger"},
                   {"how", progress_reader.loggerError()},
                   {"log", (fs::path(out_dir) / "logger.log").string()},
                   {"last_lines", nlohmann::json::array()}};
      } else {
        const std::string log = (fs::path(out_dir) / (e.name + ".log")).string();
        std::cerr << "lagrange run: process '" << e.name << "' " << e.describe()
                  << "; stopping the others. Its last lines (" << log << "):\n";
        const std::vector<std::string> tail = logTail(log, 15);
        // A program's own lines (an external controller's, a plant's): escaped.
        for (const std::string& line : tail) std::cerr << "    " << util::terminalSafe(line) << "\n";
        failure = failureRecord(e.name, e.describe(), log, tail);
      }
      for (const wiring::ChildExit& other : supervisor.stopAll(5.0))
        if (other.failed() && other.signal != SIGTERM)
          std::cerr << "lagrange run: process '" << other.name << "' " << other.describe() << "\n";
      exit_code = kExitFailed;
      break;
    }
  }
  key.reset();  // every process has ended: the run's secret goes with it
  // A plant that exited 0 before the run's every tick was recorded (a
  // program from outside can: "finished" early, ticks skipped, or no word):
  // not a success, and the plant's doing.
  if (exit_code == 0 && plant_done && runsHere(opt, "logger") && !runCompleted(out_dir, run_id)) {
    const nlohmann::json summary = thisRunsSummary(out_dir, run_id);
    const std::string how = summary.is_object() ? plantEndedEarly(summary, scenario.lastTick())
                                                : "exited with code 0 before the run's last tick (no "
                                                  "summary.json of this run says it completed)";
    if (!how.empty()) {
      const std::string log = (fs::path(out_dir) / "plant.log").string();
      std::cerr << "lagrange run: the plant " << how << "\n";
      failure = failureRecord("plant", how, log, logTail(log, 15));
      exit_code = kExitFailed;
    }
  }
  // The logger's last line (the final sample) may have come after the loop's last read.
  if (const auto latest = progress_reader.wait(0)) progress.update(latest->first, latest->second);
  progress.finish();
  close(progress_pipe[0]);
  if ((exit_code == 0 || !failure.is_null()) && runsHere(opt, "logger")) {
    try {
      addLauncherFacts(out_dir, run_id, cpu, supervision, failure, external_scheduler);
    } catch (const std::exception& e) {
      const int code = failWith("lagrange run", e);
      if (exit_code == 0) exit_code = code;
    }
  }
  if (exit_code != kExitInterrupted) writeRunReport(opt, out_dir);
  if (exit_code == 0 && !opt.quiet) {
    if (runsHere(opt, "logger"))
      printResult(out_dir);
    else
      std::cout << "this host's processes finished; the log and summary.json are where the logger ran\n";
  }
  if (exit_code != 0) std::cerr << "lagrange run: the log so far is kept in " << out_dir << "/run.lcm\n";
  return exit_code;
}
}  // namespace

namespace {
int runScenarioLocked(const RunOptions& opt) {
  try {
    for (const std::string& text : opt.checks) parseMetricCheck(text);  // a bad check stops nothing half-way
  } catch (const std::exception& e) {
    return failWith("lagrange run", e);
  }
  if (opt.check && !runsHere(opt, "logger")) {
    std::cerr << "lagrange run: --check reads the run's summary.json, which the logger writes on its own "
                 "host; expected --processes to include logger\n";
    return kExitBadInput;
  }
  if (const std::string why = checkProcesses(opt); !why.empty()) {
    std::cerr << "lagrange run: " << why << "\n";
    return kExitBadInput;
  }
  config::Scenario scenario;
  std::string out_dir;
  try {
    scenario = config::loadScenario(opt.config_path, opt.overrides);
    if (runsHere(opt, "plant") && !scenario.plant.external())
      plant::checkPlantBuilds(scenario);  // e.g. an arm plant.engine cannot simulate
    if (!opt.key_file.empty()) runtime::readKeyFile(opt.key_file);  // a bad key file stops nothing half-way
    // A CPU this machine lacks: refused here rather than by a process half-started
    // (each process checks again on its own host, for runs spread with --processes).
    if (scenario.mode == config::Mode::kRealtime)
      for (const auto& [process, cpus] : scenario.realtime.cpus)
        if (runsHere(opt, process)) transport::checkCpus(cpus, "realtime.cpus." + process);
    out_dir = prepareOutDir(opt.out_dir);
    // The run writes its own key there, in place of whatever is there.
    std::error_code ec;
    if (!opt.key_file.empty() &&
        fs::weakly_canonical(opt.key_file, ec) == fs::weakly_canonical(fs::path(out_dir) / "run.key", ec))
      throw config::ConfigError(
          "--key-file '" + opt.key_file +
          "' is the run's own key file OUT/run.key, which every run replaces with a key "
          "of its own; expected a key file outside the output directory");
  } catch (const std::exception& e) {
    return failWith("lagrange run", e);
  }
  // The launcher's lock on the output directory, for the whole run: taken
  // by the process that runs it (after the re-exec into a private network
  // namespace, which would drop it), before anything is written there.
  std::optional<logs::OutDirLock> lock;
  auto lockOutDir = [&] {
    lock.emplace(out_dir, "lagrange run");
    checkOutputPaths(out_dir, opt.report);
    // A summary.json in OUT is this run's or none: an older run's (the same
    // --run-id, a logger that died before writing) must not pass for it.
    std::error_code gone;
    fs::remove(fs::path(out_dir) / "summary.json", gone);
  };

  if (scenario.mode == config::Mode::kInproc) {
    if (!opt.processes.empty()) {
      std::cerr << "lagrange run: --processes does not apply to mode inproc (one process, no LCM)\n";
      return kExitBadInput;
    }
    lockOutDir();
    const controller::GainReport gains = checkGainsBeforeRun(scenario, opt);
    if (!gainsAllowRun(scenario, gains, opt)) return kExitBadInput;
    writeResolved(scenario, opt.config_path, out_dir);
    writeGains(scenario, gains, out_dir);  // as every run leaves it, though nothing here reads it
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    wiring::ProgressDisplay progress(scenario.duration, opt.quiet);
    const int code =
        wiring::runInProcess(scenario, gains, out_dir, progress, [] { return launcher_signal != 0; });
    progress.finish();
    if (code != kExitInterrupted) writeRunReport(opt, out_dir);
    if (code == 0 && !opt.quiet) printResult(out_dir);
    return checkMetric(opt, out_dir, code);
  }

  if (opt.private_netns && !wiring::insidePrivateNetns()) {
    const std::string why = wiring::reexecInPrivateNetns(opt.self_argv);
    std::cerr << "lagrange run: " << why << "; install util-linux or run with --no-netns\n";
    return kExitFailed;
  }
  if (opt.private_netns) {
    try {
      wiring::configureLoopbackMulticast();
    } catch (const std::exception& e) {
      return failWith("lagrange run", e);
    }
  }
  lockOutDir();
  const controller::GainReport gains = checkGainsBeforeRun(scenario, opt);
  if (!gainsAllowRun(scenario, gains, opt)) return kExitBadInput;
  const std::string resolved = writeResolved(scenario, opt.config_path, out_dir);
  const std::string gains_path = writeGains(scenario, gains, out_dir);

  return checkMetric(opt, out_dir, superviseProcesses(scenario, opt, out_dir, {resolved, gains_path}));
}
}  // namespace

// A link planted in the output directory or another run holding it is bad
// input (exit 2); a file that cannot be written (full disk, I/O error) a
// runtime fault (exit 1). Both name the file.
int runScenario(const RunOptions& opt) {
  // A run's folder is its user's: another local user reads no log, key or
  // summary of it (docs/reliability.md), unless the user asks to --share.
  // The umask reaches every process the run starts, and every file they write.
  const mode_t user_umask = opt.share ? 0 : ::umask(077);
  int code = 0;
  try {
    code = runScenarioLocked(opt);
  } catch (const std::exception& e) {
    code = failWith("lagrange run", e);
  }
  if (!opt.share) ::umask(user_umask);
  return code;
}

}  // namespace lagrange::tools
