#include "tools/tune/tune_slurm.hpp"

#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "tools/command_error.hpp"
#include "tools/tune/tune_evaluate.hpp"
#include "tools/tune/tune_files.hpp"
#include "tools/tune/tune_report.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace lagrange::tools {

namespace fs = std::filesystem;

namespace {

const std::string kTuneCommand = "lagrange tune";

volatile std::sig_atomic_t g_waiting_stopped = 0;
void stopWaiting(int) { g_waiting_stopped = 1; }

// A start's files are read only when they are what a start of this tune
// wrote there: regular files (never through a link), owned by whoever owns
// DIR/starts.json, of a size a tune writes. DIR may be on a shared file system.
constexpr std::uintmax_t kLargestStartFile = 256u << 20;

std::string readTrustedFile(const fs::path& path, uid_t owner) {
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) throw RuntimeFault(path.string() + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw BadInput(path.string() +
                   " is not a regular file (a link, a FIFO, a directory?); expected the file "
                   "lagrange tune writes there");
  if (st.st_uid != owner)
    throw BadInput(path.string() + " is owned by user " + std::to_string(st.st_uid) + ", not by user " +
                   std::to_string(owner) + " who owns the tune's starts.json; expected the tune's own files");
  if (static_cast<std::uintmax_t>(st.st_size) > kLargestStartFile)
    throw BadInput(path.string() + " is larger than 256 MiB; expected a tune's file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

fs::path startDir(const fs::path& dir, int k) { return dir / "starts" / std::to_string(k); }

// DIR/starts.json's arguments: what decides each start's search (a rerun
// must repeat them), the starts and the budget (which a rerun may change).
nlohmann::ordered_json startsArguments(const TuneOptions& o) {
  nlohmann::ordered_json a;
  a["scenario"] = fs::absolute(o.scenario).lexically_normal().string();
  a["overrides"] = o.overrides;
  a["seed"] = o.seed;
  a["span"] = o.span;
  a["global"] = o.global;
  a["require_condition"] = o.require_condition;
  a["full_runs"] = o.full_runs;
  a["starts"] = o.starts;
  a["evaluations"] = o.evaluations;
  a["minutes"] = o.minutes;
  return a;
}

struct StartsFile {
  nlohmann::ordered_json arguments;
  std::string job;  ///< the last job submitted ("" before one was)
  uid_t owner = 0;
};

void writeStartsFile(const fs::path& dir, const nlohmann::ordered_json& arguments, const std::string& job) {
  nlohmann::ordered_json j;
  j["arguments"] = arguments;
  j["job"] = job.empty() ? nlohmann::json() : nlohmann::json(job);
  util::writeOutputFile((dir / "starts.json").string(), j.dump(2) + "\n");
}

std::optional<StartsFile> readStartsFile(const fs::path& dir) {
  const fs::path path = dir / "starts.json";
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) return std::nullopt;
  StartsFile f;
  f.owner = st.st_uid;
  try {
    const nlohmann::ordered_json j = nlohmann::ordered_json::parse(readTrustedFile(path, st.st_uid));
    f.arguments = j.at("arguments");
    if (j.contains("job") && j.at("job").is_string()) f.job = j.at("job").get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    throw BadInput(path.string() + " is not a Slurm tune's starts.json (" + e.what() +
                   "); expected the file lagrange tune --slurm writes");
  }
  return f;
}

TuneOptions optionsOf(const nlohmann::ordered_json& a) {
  TuneOptions o;
  try {
    o.scenario = a.at("scenario").get<std::string>();
    o.overrides = a.at("overrides").get<std::vector<std::string>>();
    o.seed = a.at("seed").get<unsigned>();
    o.span = a.at("span").get<double>();
    o.global = a.at("global").get<int>();
    o.require_condition = a.at("require_condition").get<bool>();
    // A starts.json from before the cut has none: its starts judged every run to its end.
    o.full_runs = a.value("full_runs", true);
    o.starts = a.at("starts").get<int>();
    o.evaluations = a.at("evaluations").get<int>();
    o.minutes = a.at("minutes").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw BadInput(std::string("starts.json's arguments are not a Slurm tune's (") + e.what() +
                   "); expected the file lagrange tune --slurm writes");
  }
  if (o.starts < 1 || o.starts > 100000 ||
      static_cast<unsigned long long>(o.seed) + static_cast<unsigned long long>(o.starts) - 1 >
          std::numeric_limits<unsigned>::max())
    throw BadInput("starts.json: starts " + std::to_string(o.starts) + " from seed " +
                   std::to_string(o.seed) + "; expected 1 to 100000 starts, the last seed at most " +
                   std::to_string(std::numeric_limits<unsigned>::max()));
  return o;
}

// One start as collect finds it.
struct Start {
  bool finished = false;
  std::string not_finished;                   // why, when not
  nlohmann::json result;                      // its tune.json's result
  std::vector<nlohmann::ordered_json> lines;  // its tune.jsonl
  std::vector<TuneEvaluation> evaluations;    // the same, read
};

Start readStart(const fs::path& dir, int k, const nlohmann::ordered_json& expected,
                const nlohmann::ordered_json& budget, uid_t owner) {
  Start s;
  struct stat st {};
  if (lstat((dir / "starts").c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
    throw BadInput((dir / "starts").string() + " is not a directory (a link?); expected the starts' folder");
  const fs::path folder = startDir(dir, k);
  if (lstat(folder.c_str(), &st) != 0) {
    s.not_finished = "no folder: not started yet, or its task failed before the tune began";
    return s;
  }
  if (!S_ISDIR(st.st_mode))
    throw BadInput(folder.string() + " is not a directory (a link?); expected a start's folder");
  const fs::path json_path = folder / "tune.json";
  if (lstat(json_path.c_str(), &st) != 0) {
    s.not_finished = "no tune.json: still running, or its task failed";
    return s;
  }
  try {
    const nlohmann::json tune = nlohmann::json::parse(readTrustedFile(json_path, owner));
    if (!tune.is_object() || !tune.contains("arguments") || !tune.contains("result") ||
        !(tune["result"].is_object() || tune["result"].is_null()))
      throw BadInput(json_path.string() +
                     " is not a tune's: expected an object with `arguments` and `result`, as lagrange tune "
                     "writes");
    nlohmann::json found = tune["arguments"];
    // A start from before the cut has no `cut`: it judged every run to its end.
    if (found.is_object() && !found.contains("cut") && expected.contains("cut") &&
        expected.at("cut").is_null())
      found["cut"] = nullptr;
    if (found != nlohmann::json(expected))
      throw BadInput(json_path.string() + " holds another tune's arguments than start " + std::to_string(k) +
                     "'s (seed " + nlohmann::json(expected.at("seed")).dump() +
                     "); expected the folder this tune's start wrote");
    s.result = tune["result"];
  } catch (const nlohmann::json::exception& e) {
    throw BadInput(json_path.string() + " is not a tune's (" + e.what() +
                   "); expected the file lagrange tune writes");
  }
  // No tune.jsonl: stopped before its first evaluation.
  const fs::path jsonl_path = folder / "tune.jsonl";
  if (lstat(jsonl_path.c_str(), &st) == 0) {
    std::istringstream jsonl(readTrustedFile(jsonl_path, owner));
    long number = 0;
    for (std::string line; std::getline(jsonl, line);) {
      ++number;
      if (line.empty()) continue;
      try {
        s.lines.push_back(nlohmann::ordered_json::parse(line));
      } catch (const nlohmann::json::exception&) {
        if (jsonl.peek() == EOF) break;  // torn by an interrupt: the start resumes it
        throw BadInput(jsonl_path.string() + " line " + std::to_string(number) +
                       " is not JSON; expected the lines lagrange tune writes");
      }
      try {
        s.evaluations.push_back(evaluationFromJson(s.lines.back()));
      } catch (const BadInput& e) {
        throw BadInput(jsonl_path.string() + " line " + std::to_string(number) + ": " + e.what());
      }
    }
  }
  if (s.result.is_null()) {
    s.not_finished = "no result in its tune.json: still running, or killed (a Slurm time limit?)";
    return s;
  }
  const auto interrupted = s.result.find("interrupted");
  if (interrupted == s.result.end() || !interrupted->is_boolean())
    throw BadInput(json_path.string() +
                   ": result.interrupted is not true or false; expected the file lagrange tune writes");
  if (interrupted->get<bool>()) {
    s.not_finished = "interrupted (a Slurm time limit, scancel?)";
    return s;
  }
  const auto made_at = s.result.find("budget");
  if (made_at == s.result.end() || *made_at != nlohmann::json(budget)) {
    s.not_finished = "finished at another budget (" +
                     (made_at == s.result.end() ? std::string("not recorded") : made_at->dump()) + ", now " +
                     budget.dump() + ")";
    return s;
  }
  s.finished = true;
  return s;
}

// The evaluation of `s` that is its tune.json's best: the first feasible one with those gains.
const TuneEvaluation* bestOf(const Start& s) {
  if (!s.finished) return nullptr;
  const auto best = s.result.find("best");
  if (best == s.result.end() || !best->is_object()) return nullptr;
  const auto gains = best->find("gains");
  if (gains == best->end() || !gains->is_object()) return nullptr;
  const auto same = [&](const TuneGains& g) {
    if (gains->size() != g.size()) return false;
    for (const auto& [name, values] : g) {
      const auto found = gains->find(name);
      if (found == gains->end() || *found != nlohmann::json(values)) return false;
    }
    return true;
  };
  for (const TuneEvaluation& e : s.evaluations)
    if (e.feasible == true && e.convergence_time && same(e.gains)) return &e;
  return nullptr;
}

// "0-3,5,7-8": the starts as sbatch --array takes them (a list of every
// index would outgrow an argument's length for tens of thousands).
std::string arrayIndices(const std::vector<int>& ks) {
  std::string out;
  for (size_t i = 0; i < ks.size();) {
    size_t j = i;
    while (j + 1 < ks.size() && ks[j + 1] == ks[j] + 1) ++j;
    out += (out.empty() ? "" : ",") + std::to_string(ks[i]) + (j > i ? "-" + std::to_string(ks[j]) : "");
    i = j + 1;
  }
  return out;
}

std::string startText(int k, unsigned seed) {
  return "start " + std::to_string(k) + " (seed " + std::to_string(seed) + ")";
}

}  // namespace

int collectTune(const std::string& dir_text, bool quiet, const std::string& who) {
  const fs::path dir = fs::absolute(dir_text).lexically_normal();
  TuneOptions o;
  TuneProblem p;
  std::optional<StartsFile> starts_file;
  std::vector<Start> starts;
  try {
    starts_file = readStartsFile(dir);
    if (!starts_file)
      throw BadInput(dir.string() +
                     " holds no Slurm tune (no starts.json); expected the --out of a lagrange tune --slurm");
    o = optionsOf(starts_file->arguments);
    o.out_dir = dir.string();
    p = checkedTuneProblem(o);
    for (int k = 0; k < o.starts; ++k)
      starts.push_back(readStart(dir, k,
                                 tuneArguments(p, o.seed + static_cast<unsigned>(k), o.span, o.global),
                                 tuneBudget(o.evaluations, o.minutes), starts_file->owner));
  } catch (const std::exception& e) {
    return failWith(who, e);
  }

  // The best: the fastest of the starts' bests, the first start on a tie.
  std::optional<int> best_start;
  const TuneEvaluation* best = nullptr;
  std::vector<TuneEvaluation> all;
  std::vector<nlohmann::ordered_json> all_lines;
  std::vector<int> missing;
  long evaluations = 0;
  nlohmann::ordered_json per_start = nlohmann::ordered_json::array();
  for (int k = 0; k < o.starts; ++k) {
    const Start& s = starts[static_cast<size_t>(k)];
    all.insert(all.end(), s.evaluations.begin(), s.evaluations.end());
    all_lines.insert(all_lines.end(), s.lines.begin(), s.lines.end());
    evaluations += static_cast<long>(s.evaluations.size());
    if (!s.finished) missing.push_back(k);
    const TuneEvaluation* b = bestOf(s);
    if (b && (!best || *b->convergence_time < *best->convergence_time)) {
      best = b;
      best_start = k;
    }
    nlohmann::ordered_json row;
    row["start"] = k;
    row["seed"] = o.seed + static_cast<unsigned>(k);
    row["finished"] = s.finished;
    row["evaluations"] = s.evaluations.size();
    row["best"] = b ? nlohmann::json(side(*b)) : nlohmann::json();
    per_start.push_back(row);
  }
  // Without saturation, the limit the starts held candidates to: the input gains' peak.
  if (!p.torque_from_saturation)
    for (const auto& line : all_lines)
      if (line.contains("torque_limit") && line["torque_limit"].is_number()) {
        p.torque_limit = line["torque_limit"].get<double>();
        break;
      }

  nlohmann::ordered_json result;
  result["starts"] = per_start;
  result["evaluations"] = evaluations;
  result["missing"] = missing;
  result["input"] = all.empty() ? nlohmann::json() : nlohmann::json(side(all.front()));
  result["best_start"] = best_start ? nlohmann::json(*best_start) : nlohmann::json();
  result["best"] = best ? nlohmann::json(side(*best)) : nlohmann::json();
  try {
    nlohmann::ordered_json j;
    j["arguments"] = starts_file->arguments;
    j["result"] = result;
    util::writeOutputFile((dir / "tune.json").string(), j.dump(2) + "\n");
    const std::string not_drawn = drawFront(dir.string(), all_lines);
    if (!not_drawn.empty() && !quiet) std::cerr << who << ": " << not_drawn << "\n";
    if (best) writeTunedYaml(dir.string(), p, best->gains);
  } catch (const std::exception& e) {
    return failWith(who, e);
  }

  for (const int k : missing)
    std::cerr << who << ": " << startText(k, o.seed + static_cast<unsigned>(k))
              << " is not finished: " << starts[static_cast<size_t>(k)].not_finished << "; see "
              << (dir / "slurm").string() << "/start-" << k << ".out\n";
  const std::string rest =
      "collect again when they have run (lagrange tune collect " + dir_text +
      "), or submit the same command again to run them (each resumes its own tune.jsonl)";
  if (!best) {
    if (!missing.empty()) {
      std::cerr << who << ": no finished start found gains that pass every check (" << missing.size()
                << " of " << o.starts << " starts not finished); " << rest << "\n";
      return kExitFailed;
    }
    std::cerr << who << ": no gains passed every check in " << evaluations << " evaluations of " << o.starts
              << " starts; what binds:\n";
    for (const std::string& line : whatBinds(p, all)) std::cerr << "  - " << line << "\n";
    return kExitFailed;
  }
  if (!quiet) {
    std::cout << who << ": " << o.scenario << " (" << p.input.controller.type << ", " << p.variables.size()
              << " gains searched), " << o.starts << " starts (seeds " << o.seed << " to "
              << o.seed + static_cast<unsigned>(o.starts) - 1 << "), " << evaluations
              << " evaluations made; the best from "
              << startText(*best_start, o.seed + static_cast<unsigned>(*best_start)) << "\n";
    printSummary(all.front(), *best, p);
    std::cout << "wrote " << dir_text << "/tuned.yaml (lagrange run / check-gains it as it is), tune.json, "
              << "front.png; each start's own in " << dir_text << "/starts/K\n";
  }
  if (!missing.empty()) {
    std::cerr << who << ": " << missing.size() << " of " << o.starts
              << " starts not finished: tuned.yaml holds the best of the others; " << rest << "\n";
    return kExitFailed;
  }
  return kExitOk;
}

int runTuneSlurm(const TuneOptions& given) {
  TuneOptions o = given;
  const fs::path dir = fs::absolute(o.out_dir).lexically_normal();
  if (o.starts == 0) o.starts = kDefaultStarts;
  nlohmann::ordered_json arguments;
  std::vector<int> to_run;  // the starts to submit
  std::string previous_job;
  try {
    if (o.starts < 1 || o.starts > 100000)
      throw BadInput("--starts " + std::to_string(o.starts) + ": expected 1 to 100000");
    if (static_cast<unsigned long long>(o.seed) + static_cast<unsigned long long>(o.starts) - 1 >
        std::numeric_limits<unsigned>::max())
      throw BadInput("--seed " + std::to_string(o.seed) + " with --starts " + std::to_string(o.starts) +
                     ": the last start's seed, seed + starts - 1, is over " +
                     std::to_string(std::numeric_limits<unsigned>::max()) + "; expected a smaller --seed");
    const TuneProblem p = checkedTuneProblem(o);
    util::makeOutputDirectories(dir.string());
    if (fs::exists(fs::symlink_status(dir / "tune.jsonl")))
      throw BadInput(o.out_dir +
                     " holds a tune run here, not on Slurm (tune.jsonl); expected another --out, or the "
                     "same command without --slurm to resume it");
    arguments = startsArguments(o);
    std::optional<StartsFile> before = readStartsFile(dir);
    if (before) {
      // A starts.json from before the cut has no full_runs: its starts judged every run to its end.
      if (!before->arguments.contains("full_runs") && !o.full_runs)
        throw BadInput(olderObjectiveText(o.out_dir, "Slurm tune") +
                       "; expected --full-runs to resume it, or another --out");
      before->arguments.emplace("full_runs", true);
      for (const char* key :
           {"scenario", "overrides", "seed", "span", "global", "require_condition", "full_runs"})
        if (!before->arguments.contains(key) || before->arguments.at(key) != arguments.at(key))
          throw BadInput(
              o.out_dir + " holds a Slurm tune with other arguments (" + key + ": " +
              (before->arguments.contains(key) ? before->arguments.at(key).dump() : "none") + ", now " +
              arguments.at(key).dump() +
              "); a rerun repeats the scenario, --set, --seed, --span, --global, "
              "--require-condition and --full-runs (--starts and the budget may change); expected those, or "
              "another --out");
      // Two tasks of one start would append to one tune.jsonl.
      previous_job = before->job;
      if (!previous_job.empty() && wiring::slurmJobQueued(previous_job))
        throw BadInput(
            o.out_dir + ": its Slurm job " + previous_job +
            " is still queued or running (squeue lists it); expected it to end first (or scancel " +
            previous_job + "), then the same command again");
    }
    // A start finished at this budget is not submitted again; one finished
    // at another resumes from its tune.jsonl.
    const uid_t owner = before ? before->owner : geteuid();
    const nlohmann::ordered_json budget = tuneBudget(o.evaluations, o.minutes);
    for (int k = 0; k < o.starts; ++k)
      if (!readStart(dir, k, tuneArguments(p, o.seed + static_cast<unsigned>(k), o.span, o.global), budget,
                     owner)
               .finished)
        to_run.push_back(k);
    if (to_run.empty()) writeStartsFile(dir, arguments, previous_job);
  } catch (const std::exception& e) {
    return failWith(kTuneCommand, e);
  }
  if (to_run.empty()) {
    if (!o.quiet)
      std::cout << kTuneCommand << ": every start of " << o.out_dir << " is finished; collecting\n";
    return collectTune(o.out_dir, o.quiet, kTuneCommand);
  }

  const std::string indices = arrayIndices(to_run);
  const fs::path slurm = dir / "slurm";
  const fs::path sbatch_out = slurm / "sbatch.out";
  pid_t pid = -1;
  wiring::SlurmArray array;
  try {
    util::makeOutputDirectory(slurm.string());  // never a planted link (Slurm writes its outputs there)
    util::makeOutputDirectory((dir / "starts").string());
    std::string command = wiring::shellQuote(o.self_exe) + " tune " +
                          wiring::shellQuote(fs::absolute(o.scenario).lexically_normal().string());
    for (const std::string& s : o.overrides) command += " --set " + wiring::shellQuote(s);
    command += " --out " + wiring::shellQuote((dir / "starts").string()) + "/\"$k\" --seed \"$((" +
               std::to_string(o.seed) + " + k))\"";
    if (o.evaluations > 0) command += " --evaluations " + std::to_string(o.evaluations);
    if (o.minutes > 0.0) command += " --minutes " + nlohmann::json(o.minutes).dump();
    command += " --span " + nlohmann::json(o.span).dump();
    if (o.global > 0) command += " --global " + std::to_string(o.global);
    if (o.require_condition) command += " --require-condition";
    if (o.full_runs) command += " --full-runs";
    // The task's CPUs, not the node's cores: a tune at -j 1 on a 64-core
    // node given one CPU is as fast as one at -j 64 there, and gives the
    // same evaluations whatever -j.
    command += o.jobs > 0 ? " -j " + std::to_string(o.jobs) : " -j \"${SLURM_CPUS_PER_TASK:-1}\"";
    // (No path in the comment: a newline in one would end it.)
    wiring::writeJobScript(
        (slurm / "start.sh").string(),
        "#!/bin/sh\n# One start of a lagrange tune: Slurm array task K searches from seed " +
            std::to_string(o.seed) +
            " + K into OUT/starts/K (docs/tuning.md).\nk=\"$SLURM_ARRAY_TASK_ID\"\nexec " + command + "\n");
    array.job_name = "lagrange-tune";
    array.indices = indices;
    array.script = (slurm / "start.sh").string();
    array.output = (slurm / "start-%a.out").string();
    array.chdir = dir.string();
    array.sbatch_output = sbatch_out.string();
    pid = wiring::submitSlurmArray(array, o.slurm_options);
  } catch (const std::exception& e) {
    return failWith(kTuneCommand, e);
  }
  g_waiting_stopped = 0;
  std::signal(SIGINT, stopWaiting);
  std::signal(SIGTERM, stopWaiting);
  const auto restoreSignals = [] {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  };
  // starts.json with the new budget and the job only once submitted: a
  // refused submission leaves the tune as it was.
  struct StartsNotWritten {
    std::string job;
    std::exception_ptr error;
  };
  wiring::SlurmWait wait;
  try {
    wait = wiring::waitForSlurmArray(
        pid, array,
        [&](const std::string& submitted) {
          try {
            writeStartsFile(dir, arguments, submitted);
          } catch (const std::exception&) {
            throw StartsNotWritten{submitted, std::current_exception()};
          }
          if (!o.quiet)
            std::cout << kTuneCommand << ": submitted Slurm job " << submitted << ", " << to_run.size()
                      << " array tasks (starts " << indices << " of " << o.starts << ")\n"
                      << std::flush;
        },
        {}, [] { return g_waiting_stopped != 0; });
  } catch (const StartsNotWritten& not_written) {
    restoreSignals();
    std::cerr << kTuneCommand << ": submitted Slurm job " << not_written.job << ", but ";
    try {
      std::rethrow_exception(not_written.error);
    } catch (const std::exception& e) {
      return failWith("writing starts.json", e);
    }
  }
  restoreSignals();
  const std::string& job = wait.job;
  const int wstatus = wait.wstatus;
  if (wait.stopped) {
    std::cerr << kTuneCommand << ": stopped waiting; job " << (job.empty() ? "?" : job)
              << " keeps running (scancel it to stop it); once it has ended: lagrange tune collect "
              << o.out_dir << "\n";
    return kExitInterrupted;
  }
  if (job.empty()) {
    std::cerr << kTuneCommand << ": sbatch " << wiring::waitStatusText(wstatus)
              << " without submitting a job:\n"
              << wiring::sbatchOutputOf(array);
    return kExitFailed;
  }
  if (o.slurm_options.no_wait) {
    std::cout << kTuneCommand << ": when job " << job << " has ended: lagrange tune collect " << o.out_dir
              << "\n";
    return kExitOk;
  }
  // sbatch --wait exits non-zero when a task did -- a start that found
  // nothing exits 1 -- so what each start did is collect's to say.
  return collectTune(o.out_dir, o.quiet, kTuneCommand);
}

}  // namespace lagrange::tools
