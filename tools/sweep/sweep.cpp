#include "tools/sweep/sweep.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "logs/out_dir_lock.hpp"
#include "tools/command_error.hpp"
#include "tools/sweep/sweep_files.hpp"
#include "tools/sweep/sweep_maps.hpp"
#include "tools/sweep/sweep_plan.hpp"
#include "tools/sweep/sweep_plan_file.hpp"
#include "tools/sweep/sweep_progress.hpp"
#include "tools/sweep/sweep_runner.hpp"
#include "tools/sweep/sweep_store.hpp"
#include "util/error.hpp"
#include "util/jobs.hpp"
#include "util/output_file.hpp"
#include "util/terminal_text.hpp"
#include "wiring/slurm_array.hpp"
#include "wiring/spawn_logged.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;
using config::ConfigError;

std::atomic<int> sweep_signal{0};
void onSignal(int sig) { sweep_signal = sig; }
bool stopRequested() { return sweep_signal != 0; }

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// OUT/plan.json: written on the first start; on a restart it must be the
// plan the sweep file makes now, or OUT is another sweep's. Compared and
// written a line at a time, never held whole. Returns the SHA-256 of the
// plan.json on disk (what the shards will read).
std::string prepareOutDir(const std::string& out_dir, const SweepPlan& plan) {
  util::makeOutputDirectory(out_dir + "/rows");  // never a planted link
  const fs::path plan_path = fs::path(out_dir) / "plan.json";
  if (fs::exists(fs::symlink_status(plan_path))) {
    const PlanFile on_disk(plan_path.string());
    const long rows = static_cast<long>(plan.rows.size());
    long lines = 0;
    bool same = true;
    const long long read = on_disk.forEachLine([&](long number, const std::string& line) {
      lines = number;
      same = number <= rows + 1 &&
             samePlanText(line, number == 1 ? planHeaderJson(plan) : planRowJson(plan.rows[number - 2]));
      return same;
    });
    if (!same || lines != rows + 1 || read != on_disk.size())
      throw ConfigError("--out " + out_dir + " holds another sweep (its plan.json differs from the plan of " +
                        plan.spec.file +
                        " as it is now); expected the same sweep file and scenario to resume it, or a new "
                        "--out directory");
    return on_disk.sha256();
  }
  const std::string digest = writePlanFile(plan, plan_path.string() + ".tmp");
  fs::rename(plan_path.string() + ".tmp", plan_path);
  util::writeOutputFile((fs::path(out_dir) / "sweep.yaml").string(), readFile(plan.spec.file));
  return digest;
}

// What binds a shard to the plan its sweep launched (issue #44): SHA-256 of
// plan.json's bytes, on the shard's command line -- a plan.json planted in a
// shared folder afterwards (Slurm's array tasks start later, anywhere) names
// other scenarios, overrides and external commands, and a shard that ran it
// would start programs nobody named. OUT/plan.json is opened and hashed
// here, and every piece of it a shard uses is checked against that hashing
// (sweep_plan_file.hpp).
PlanFile openPlan(const std::string& out_dir) {
  const fs::path plan_path = fs::path(out_dir) / "plan.json";
  if (!fs::exists(fs::symlink_status(plan_path)))
    throw ConfigError(out_dir +
                      " is not a sweep's output directory: it has no plan.json; expected the --out "
                      "directory of lagrange sweep");
  return PlanFile(plan_path.string());
}

// The plan in OUT/plan.json, every row of it checked, none held.
SweepPlan loadPlan(const std::string& out_dir) {
  const PlanFile file = openPlan(out_dir);
  SweepPlan plan = file.header();
  file.forEachRow(plan, [](const SweepRow&) { return true; });
  return plan;
}

// What finish found: rows of the plan not in OUT/rows, and lines or files
// there refused (not this sweep's).
struct Finished {
  long missing = 0;
  long refused = 0;
  long failed_rows = 0;  // in the table with status `failed`: run, and could not be made
  int exitCode(bool failed) const {
    if (refused > 0) return kExitBadInput;
    return failed || missing > 0 || failed_rows > 0 ? kExitFailed : kExitOk;
  }
};

// Table and maps from what is in OUT/rows.
Finished finish(const std::string& out_dir, const SweepPlan& plan, bool quiet, const std::string& who,
                bool collecting = false) {
  const FinishedRows finished =
      readFinishedRows(out_dir, static_cast<long>(plan.rows.size()), /*keep_rows=*/true, plan.param_columns);
  std::error_code ec;
  const auto& rows = finished.rows;
  if (finished.refused > 0) {
    std::cerr << who << finished.refused
              << (finished.refused == 1 ? " line or file in " : " lines or files in ")
              << (fs::path(out_dir) / "rows").string() << (finished.refused == 1 ? " was" : " were")
              << " refused, not rows of this sweep's plan, and left out of the table:\n";
    for (const std::string& why : finished.refusals)
      std::cerr << who << "  " << util::terminalSafeLines(why) << "\n";
    if (finished.refused > static_cast<long>(finished.refusals.size()))
      std::cerr << who << "  ... and " << finished.refused - static_cast<long>(finished.refusals.size())
                << " more\n";
  }

  // A table is never replaced by what a folder with refused files or lines
  // gives (issue #53 item 7: a refused rows file made collect rewrite a good
  // sweep.csv with 0 rows): it and the maps stay as they were, byte for
  // byte. Without a table yet, the rows that passed make one.
  const fs::path csv = fs::path(out_dir) / "sweep.csv", jsonl = fs::path(out_dir) / "sweep.jsonl";
  const bool keep_table = finished.refused > 0 && (fs::exists(fs::symlink_status(csv, ec)) ||
                                                   fs::exists(fs::symlink_status(jsonl, ec)));
  if (!keep_table) writeSweepTable(out_dir, plan, rows);
  // OUT/external/ keeps only the external-controller rows that did not
  // complete or were stopped midway (sweep_runner.cpp): gone when none
  // left anything (remove() leaves a directory that is not empty).
  fs::remove(fs::path(out_dir) / "external", ec);
  long diverged = 0, converged = 0, failed_rows = 0;
  for (const auto& [i, r] : rows) {
    diverged += r.value("diverged", false);
    converged += r.value("converged", false);
    const auto status = r.find("status");
    failed_rows += status != r.end() && status->is_string() && *status == "failed";
  }
  const long missing = static_cast<long>(plan.rows.size()) - static_cast<long>(rows.size());
  if (keep_table)
    std::cerr << who << csv.string() << " and sweep.jsonl were left as they were, not rewritten while "
              << "something in " << (fs::path(out_dir) / "rows").string()
              << " is refused; remove or fix what is named above, then collect again\n";
  if (!quiet) {
    std::cout << who << rows.size() << " of " << plan.rows.size() << " runs "
              << (keep_table ? "read from " + (fs::path(out_dir) / "rows").string() + " (the table kept)"
                             : "in " + csv.string() + " (and sweep.jsonl)")
              << ": " << converged << " converged, " << diverged << " diverged, " << failed_rows
              << " failed, " << static_cast<long>(rows.size()) - converged - diverged - failed_rows
              << " neither"
              << (finished.refused > 0 ? "; " + std::to_string(finished.refused) + " refused (above)" : "")
              << "\n";
  }
  // A failed row is done (a restart does not run it again: it would fail the
  // same way); why is in its stop_reason, the first few said here.
  long shown_failures = 0;
  for (const auto& [i, r] : rows) {
    const auto status = r.find("status");
    if (status == r.end() || !status->is_string() || *status != "failed" || shown_failures++ >= 3) continue;
    const auto reason = r.find("stop_reason");
    std::cerr << who << "row " << i << " failed: "
              << (reason != r.end() && reason->is_string()  // a process's last line, among others
                      ? util::terminalSafeLines(reason->get<std::string>().substr(0, 400))
                      : std::string("(no reason recorded)"))
              << "\n";
  }
  if (failed_rows > 3)
    std::cerr << who << "... and " << failed_rows - 3
              << " more failed rows (column stop_reason of sweep.csv)\n";
  try {  // the maps go with the table: kept with it
    const SweepMaps maps = keep_table ? SweepMaps{} : drawSweepMaps(out_dir, plan, rows);
    if (!quiet) {
      for (const std::string& png : maps.plots.written) std::cout << who << "wrote " << png << "\n";
      for (const std::string& why : maps.not_drawn)
        std::cout << who << "map not drawn: " << util::terminalSafeLines(why) << "\n";
      for (const std::string& note : maps.notes)
        std::cout << who << "map note: " << util::terminalSafeLines(note) << "\n";
    }
    for (const std::string& png : maps.plots.failed)
      std::cerr << who << "gnuplot could not draw " << png << " (see " << maps.plots.log << ")\n";
  } catch (const PlotError& e) {
    std::cerr << who << "no maps: " << util::terminalSafeLines(e.what()) << "\n";
  }
  if (missing > 0) {
    std::string list;
    int shown = 0;
    for (long i = 0; i < static_cast<long>(plan.rows.size()) && shown < 10; ++i)
      if (!rows.count(i)) list += (shown++ ? ", " : "") + std::to_string(i);
    std::cerr << who << missing << " runs are not done yet (" << list << (missing > 10 ? ", ..." : "")
              << "); "
              << (collecting
                      ? "a Slurm job may still be running them (squeue); once no task of the sweep runs, "
                        "the same lagrange sweep command runs what is missing\n"
                      : "run the same lagrange sweep command again to run them\n");
  }
  return {missing, finished.refused, failed_rows};
}

// Local: shards as processes, one per core; progress from the rows files.
int runLocal(const SweepOptions& o, const SweepPlan& plan, long remaining, const std::string& plan_digest) {
  const int n = static_cast<int>(std::min<long>(util::jobsOrCores(o.jobs), remaining));
  util::makeOutputDirectory((fs::path(o.out_dir) / "logs").string());  // never a planted link
  std::map<pid_t, int> running;
  for (int k = 0; k < n; ++k) {
    const std::string log =
        (fs::path(o.out_dir) / "logs" / ("shard-" + std::to_string(k) + "-of-" + std::to_string(n) + ".log"))
            .string();
    running[wiring::spawnLogged(
        {o.self_exe, "sweep-shard", o.out_dir, "--shard", std::to_string(k), "--of", std::to_string(n),
         "--parent", std::to_string(getpid()), "--plan-digest", plan_digest},
        {log, /*append=*/true})] = k;
  }
  RowCounter counter(o.out_dir);
  SweepProgress progress(static_cast<long>(plan.rows.size()), counter.count().rows, o.quiet);
  bool forwarded = false, failed = false;
  while (!running.empty()) {
    int wstatus = 0;
    const pid_t pid = waitpid(-1, &wstatus, WNOHANG);
    if (pid > 0 && running.count(pid)) {
      const int k = running[pid];
      running.erase(pid);
      const bool stopped = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == kExitInterrupted;
      if (!(WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0) && !(stopped && sweep_signal)) {
        failed = true;
        progress.interrupt();
        std::cerr << "lagrange sweep: shard " << k << " of " << n << " " << wiring::waitStatusText(wstatus)
                  << "; see " << (fs::path(o.out_dir) / "logs").string() << "\n";
      }
      continue;
    }
    if (sweep_signal && !forwarded) {  // stop the shards; each keeps the rows it finished
      for (const auto& [p, k] : running) kill(p, SIGTERM);
      forwarded = true;
    }
    const RowCount c = counter.count();
    progress.update(c.rows, c.diverged);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  const RowCount end = counter.count();
  progress.finish(end.rows, end.diverged);
  const Finished done = finish(o.out_dir, plan, o.quiet, "lagrange sweep: ");
  if (sweep_signal) return kExitInterrupted;
  return done.exitCode(failed);
}

// --slurm: a job array of shards, then (unless --no-wait) wait for it.
int runSlurm(const SweepOptions& o, const SweepPlan& plan, long remaining, const std::string& plan_digest) {
  const int n = static_cast<int>(std::min<long>(o.shards > 0 ? o.shards : 64, remaining));
  const fs::path dir = fs::absolute(o.out_dir);
  const fs::path slurm = dir / "slurm";
  util::makeOutputDirectory(slurm.string());  // never a planted link (Slurm writes its outputs there)
  const fs::path script = slurm / "shard.sh";
  wiring::writeJobScript(
      script.string(),
      "#!/bin/sh\n# One shard of a lagrange sweep: Slurm array task K runs rows with index % " +
          std::to_string(n) + " == K.\nexec " + wiring::shellQuote(o.self_exe) + " sweep-shard " +
          wiring::shellQuote(dir.string()) + " --shard \"$SLURM_ARRAY_TASK_ID\" --of " + std::to_string(n) +
          " --plan-digest " + plan_digest + "\n");
  const fs::path sbatch_out = slurm / "sbatch.out";
  wiring::SlurmArray array;
  array.job_name = "lagrange-sweep";
  array.indices = "0-" + std::to_string(n - 1);
  array.script = script.string();
  array.output = (slurm / "shard-%a.out").string();
  array.chdir = dir.string();
  array.sbatch_output = sbatch_out.string();
  const pid_t pid = wiring::submitSlurmArray(array, o.slurm_options);
  RowCounter counter(o.out_dir);
  SweepProgress progress(static_cast<long>(plan.rows.size()), counter.count().rows,
                         o.quiet || o.slurm_options.no_wait);
  const wiring::SlurmWait wait = wiring::waitForSlurmArray(
      pid, array,
      [&](const std::string& submitted) {
        if (o.quiet) return;
        progress.interrupt();
        std::cout << "lagrange sweep: submitted Slurm job " << submitted << ", " << n << " array tasks ("
                  << remaining << " runs)\n"
                  << std::flush;
      },
      [&] {
        const RowCount c = counter.count();
        progress.update(c.rows, c.diverged);
      },
      stopRequested);
  const std::string& job = wait.job;
  const int wstatus = wait.wstatus;
  if (wait.stopped) {
    progress.interrupt();
    std::cerr << "lagrange sweep: stopped waiting; job " << (job.empty() ? "?" : job)
              << " keeps running (scancel it to stop it); then: lagrange sweep collect " << o.out_dir << "\n";
    return kExitInterrupted;
  }
  const RowCount end = counter.count();
  progress.finish(end.rows, end.diverged);
  const bool sbatch_ok = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0;
  if (job.empty()) {  // not submitted
    std::cerr << "lagrange sweep: sbatch " << wiring::waitStatusText(wstatus)
              << " without submitting a job:\n"
              << wiring::sbatchOutputOf(array);
    return kExitFailed;
  }
  if (o.slurm_options.no_wait) {
    std::cout << "lagrange sweep: when job " << job << " has ended: lagrange sweep collect " << o.out_dir
              << "\n";
    return kExitOk;
  }
  if (!sbatch_ok)  // sbatch --wait exits non-zero when a task did
    std::cerr << "lagrange sweep: a task of job " << job << " failed (sbatch --wait "
              << wiring::waitStatusText(wstatus) << "); see " << (slurm / "shard-*.out").string() << "\n";
  return finish(o.out_dir, plan, o.quiet, "lagrange sweep: ").exitCode(false);
}

}  // namespace

int runSweep(const SweepOptions& o) {
  std::optional<logs::OutDirLock> lock;
  SweepPlan plan;
  std::string plan_digest;  // of plan.json as the shards will read it
  try {
    plan = planSweep(readSweepSpec(o.sweep_file));
    if (o.dry_run) {
      std::cout << "lagrange sweep: " << plan.rows.size() << " runs of " << plan.spec.scenario_path
                << ", every one checked; columns: ";
      for (const std::string& c : plan.param_columns) std::cout << c << " ";
      std::cout << "\n";
      return kExitOk;
    }
    // One sweep at a time in OUT: two would run the same rows. Locked
    // before plan.json is written (logs/out_dir_lock.hpp: names the
    // holder's pid, dies with it).
    fs::create_directories(o.out_dir);
    lock.emplace(o.out_dir, "lagrange sweep");
    plan_digest = prepareOutDir(o.out_dir, plan);
  } catch (const std::exception& e) {
    return failWith("lagrange sweep", e);
  }
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  try {
    const long remaining =
        static_cast<long>(plan.rows.size()) -
        readFinishedRows(o.out_dir, static_cast<long>(plan.rows.size()), /*keep_rows=*/false).count;
    if (!o.quiet)
      std::cout << "lagrange sweep: " << plan.rows.size() << " runs of " << plan.spec.scenario_path << ", "
                << remaining << " to run" << (o.slurm ? " on Slurm" : "") << "\n"
                << std::flush;
    if (remaining == 0) return finish(o.out_dir, plan, o.quiet, "lagrange sweep: ").exitCode(false);
    return o.slurm ? runSlurm(o, plan, remaining, plan_digest) : runLocal(o, plan, remaining, plan_digest);
  } catch (const std::exception& e) {
    return failWith("lagrange sweep", e);
  }
}

int collectSweep(const std::string& out_dir, bool quiet) {
  try {
    const SweepPlan plan = loadPlan(out_dir);
    return finish(out_dir, plan, quiet, "lagrange sweep collect: ", /*collecting=*/true).exitCode(false);
  } catch (const std::exception& e) {
    return failWith("lagrange sweep collect", e);
  }
}

int runSweepShard(const std::string& out_dir, int shard, int of, const std::string& plan_digest, int parent,
                  const std::string& self_exe) {
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  // A local shard ends with its sweep: killed, the sweep leaves no shard
  // behind to write rows while a restart runs them again.
  if (parent > 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) return kExitInterrupted;
  }
  try {
    if (of < 1 || shard < 0 || shard >= of)
      throw ConfigError("--shard " + std::to_string(shard) + " --of " + std::to_string(of) +
                        ": expected 0 <= K < N");
    const PlanFile file = openPlan(out_dir);
    if (file.sha256() != plan_digest)
      throw ConfigError(
          file.path() + " is not the plan this shard was started for (its SHA-256 is " + file.sha256() +
          ", expected " + plan_digest +
          " from lagrange sweep): it was replaced after the sweep started; nothing of it is run");
    const SweepPlan plan = file.header();
    if (scenarioDigest(plan.spec.scenario_path) != plan.spec.scenario_digest)
      throw ConfigError(plan.spec.scenario_path +
                        " has changed since the sweep was planned; expected it as it was (its rows would "
                        "mix two scenarios), or a new sweep in a new --out directory");
    const std::vector<bool> done =
        readFinishedRows(out_dir, static_cast<long>(plan.rows.size()), /*keep_rows=*/false).done;
    RowWriter writer((fs::path(out_dir) / "rows" /
                      ("shard-" + std::to_string(shard) + "-of-" + std::to_string(of) + ".jsonl"))
                         .string());
    SweepRunner runner(plan, out_dir, self_exe);
    long ran = 0;
    // The rows read from plan.json as they come, every piece of it checked
    // against the digest above (sweep_plan_file.hpp).
    file.forEachRow(plan, [&](const SweepRow& row) {
      if (row.index % of != shard || done[static_cast<size_t>(row.index)]) return true;
      if (stopRequested()) return false;
      std::optional<nlohmann::ordered_json> result;
      try {
        result = runner.run(row, stopRequested);
      } catch (const std::exception& e) {  // a result too: the row says why, and a restart does not retry it
        result = runner.failedRow(row, e.what());
      }
      if (!result) return false;  // stopped midway: the row is run again on a restart
      writer.append(*result);
      ++ran;
      return true;
    });
    std::cout << "shard " << shard << " of " << of << ": ran " << ran << " runs"
              << (stopRequested() ? " (stopped by a signal)" : "") << "\n";
    return stopRequested() ? kExitInterrupted : kExitOk;
  } catch (const std::exception& e) {
    return failWith("lagrange sweep-shard", e);
  }
}

}  // namespace lagrange::tools
