#include "tools/sweep/sweep_runner.hpp"

#include <sys/wait.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <thread>

#include "controller/paper_section.hpp"
#include "logger/summary.hpp"
#include "logger/verdict.hpp"
#include "model/reference.hpp"
#include "tools/sweep/sweep_files.hpp"
#include "tools/sweep/sweep_values.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"
#include "wiring/inproc_runner.hpp"
#include "wiring/sampled_simulation.hpp"
#include "wiring/spawn_logged.hpp"

namespace lagrange::tools {

namespace {

// The first error line `lagrange run` wrote into a row's run.out (after
// "; "), or nothing: what a failed row says when its summary does not.
std::string launcherError(const std::filesystem::path& run_out) {
  std::string error;  // a row's folder may be in a shared one: read as any file there
  const std::optional<std::string> text = readSweepFile(run_out.string(), "a row's run.out", 1 << 20, error);
  std::istringstream in(text.value_or(""));
  for (std::string line; std::getline(in, line);)
    if (line.rfind("lagrange run: ", 0) == 0 && line.find("the log so far is kept") == std::string::npos)
      return "; " + line.substr(0, 300);
  return "";
}

// ||(q~(0), q~'(0), qc(0))||: the closed loop's initial state, the plant's
// error and (the paper's controllers) the stage-0 filter state. r0: the
// reference at t = 0.
double initialStateNorm(const config::Scenario& s, const model::ReferenceSample& r0) {
  const Eigen::VectorXd error = s.initial_state.q - r0.q();
  const double e = error.norm(), e_rate = (s.initial_state.qdot - r0.qd()).norm();
  double sq = e * e + e_rate * e_rate;
  if (controller::isPaperType(s.controller.type)) {
    const controller::PaperSettings& c = controller::paperSettings(s);
    sq += (c.initial_filter_state ? *c.initial_filter_state : Eigen::VectorXd(-c.gains.b.cwiseProduct(error)))
              .squaredNorm();
  }
  return std::sqrt(sq);
}

// The kind (logger/verdict.hpp) of the finding verdict_reason quotes
// (logger::likeliestReason): the first reason's, or a met run's first
// warning's; null when there is neither. The maps draw a row by it.
nlohmann::json likeliestKind(const nlohmann::json& verdict) {
  if (!verdict.is_object()) return nullptr;
  for (const char* list : {"reasons", "warnings"}) {
    const auto found = verdict.find(list);
    if (found == verdict.end() || !found->is_array() || found->empty()) continue;
    const nlohmann::json& first = found->front();
    if (first.is_object() && first.contains("kind") && first.at("kind").is_string()) return first.at("kind");
    return nullptr;
  }
  return nullptr;
}

}  // namespace

const std::vector<std::string>& resultColumns() {
  static const std::vector<std::string> columns = {"status",
                                                   "diverged",
                                                   "converged",
                                                   "convergence_time",
                                                   "final_error",
                                                   "max_error",
                                                   "initial_error",
                                                   "x0_norm",
                                                   "gains_checked",
                                                   "condition_holds",
                                                   "gain_margin",
                                                   "linearised_verdict",
                                                   "spectral_radius",
                                                   "sampled_verdict",
                                                   "fine_rate",
                                                   "fine_convergence_time",
                                                   "fine_error_last_second",
                                                   "wall_time",
                                                   "stop_reason",
                                                   "verdict",
                                                   "verdict_reason",
                                                   "verdict_kind"};
  return columns;
}

const controller::GainReport& SweepRunner::gainsOf(const config::Scenario& s) {
  config::Scenario key = s;  // the check reads the robot, reference, gains and rate, never the initial state
  key.initial_state.q.setZero();
  key.initial_state.qdot.setZero();
  key.initial_state.motor_q.setZero();
  key.initial_state.motor_qdot.setZero();
  if (controller::isPaperType(key.controller.type)) {
    controller::PaperSettings& c = controller::paperSettings(key);
    c.initial_filter_state.reset();
    c.stage_starts.clear();
  }
  key.actuator.initial_state.setZero();
  const std::string text = config::toYaml(key);
  auto found = gains_.find(text);
  if (found == gains_.end()) found = gains_.emplace(text, controller::checkGains(s)).first;
  return found->second;
}

nlohmann::ordered_json SweepRunner::failedRow(const SweepRow& row, const std::string& why) const {
  nlohmann::ordered_json j;
  j["index"] = row.index;
  for (size_t i = 0; i < plan_.param_columns.size(); ++i)
    j[plan_.param_columns[i]] = typedParam(row.params.at(i));  // sweep_values.hpp
  for (const std::string& c : resultColumns()) j[c] = nullptr;
  j["status"] = "failed";
  j["diverged"] = false;
  j["converged"] = false;
  j["stop_reason"] = why;
  return j;
}

std::optional<nlohmann::ordered_json> SweepRunner::run(const SweepRow& row, bool (*stop_requested)()) {
  const auto start = std::chrono::steady_clock::now();
  config::Scenario s = config::loadScenario(plan_.spec.scenario_path, row.overrides);
  // A program of its own (controller or plant): lockstep over LCM.
  const bool external = s.controller.type == "external" || s.plant.external();
  // The sampled-data check examines the wiring that runs: in process, or
  // an external program's lockstep run (runExternal's --mode lockstep).
  s.mode = external ? config::Mode::kLockstep : config::Mode::kInproc;
  const controller::GainReport& gains = gainsOf(s);
  const wiring::InProcessOutcome o = external
                                         ? runExternal(row, stop_requested)
                                         : wiring::simulateInProcess(s, nullptr, nullptr, stop_requested);
  if (o.status == "interrupted") return std::nullopt;
  if (o.status == "failed") return failedRow(row, o.stop_message);  // its numbers are no result

  const model::ReferenceSample r0 = model::Reference(s.reference).evaluate(0.0, 1);
  nlohmann::ordered_json j;
  j["index"] = row.index;
  for (size_t i = 0; i < plan_.param_columns.size(); ++i)
    j[plan_.param_columns[i]] = typedParam(row.params.at(i));  // sweep_values.hpp
  const auto finiteOrNull = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  j["status"] = o.status;
  j["diverged"] = o.status == "diverged";
  j["converged"] = o.tracking.convergence_time.has_value();
  j["convergence_time"] =
      o.tracking.convergence_time ? nlohmann::json(*o.tracking.convergence_time) : nlohmann::json();
  j["final_error"] = finiteOrNull(o.tracking.final_error);
  j["max_error"] = finiteOrNull(o.tracking.max_error);
  j["initial_error"] = (s.initial_state.q - r0.q()).norm();
  j["x0_norm"] = initialStateNorm(s, r0);
  j["gains_checked"] = !gains.unchecked;
  j["condition_holds"] = gains.unchecked ? nlohmann::json() : nlohmann::json(gains.holds());
  j["gain_margin"] = gains.unchecked ? nlohmann::json() : finiteOrNull(gains.margin());
  j["linearised_verdict"] = gains.sampled.verdict.empty() ? "not assessed" : gains.sampled.verdict;
  j["spectral_radius"] = gains.sampled.verdict == "adequate" || gains.sampled.verdict == "slow" ||
                                 gains.sampled.verdict == "unstable"
                             ? finiteOrNull(gains.sampled.spectral_radius)
                             : nlohmann::json();
  for (const char* column :
       {"sampled_verdict", "fine_rate", "fine_convergence_time", "fine_error_last_second"})
    j[column] = nullptr;                   // in the table's order
  if (plan_.spec.simulate_sampled_data) {  // this run against the same loop at a fine rate
    controller::SampledSimulation check;
    try {
      check = wiring::judgeRun(s,
                               {o.status == "completed" ? "completed" : "diverged",
                                o.tracking.convergence_time, o.tracking.rms_last_second},
                               stop_requested);
    } catch (const wiring::SimulationStopped&) {
      return std::nullopt;  // stopped midway: the row is run again on a restart
    }
    if (stop_requested && stop_requested()) return std::nullopt;
    j["sampled_verdict"] = check.verdict;
    if (!check.starts.empty()) {
      const controller::SampledSimulation::Start& st = check.starts.front();
      j["fine_rate"] = check.fine_rate;
      j["fine_convergence_time"] = st.fine_time ? nlohmann::json(*st.fine_time) : nlohmann::json();
      j["fine_error_last_second"] = finiteOrNull(st.fine_error);
    }
  }
  j["wall_time"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  j["stop_reason"] = o.stop_message;
  // The run's verdict as `lagrange run` would write it (logger/verdict.hpp):
  // an in-process row's summary made here, an external row's from its run.
  nlohmann::json verdict = external_verdict_;
  if (!external) {
    logger::RunFacts facts;
    facts.status = o.status;
    facts.wall_time = o.wall_time;
    verdict = logger::makeSummary(s, o.tracking, gains, facts)["verdict"];
  }
  j["verdict"] = verdict.is_object() ? verdict.value("tracking", nlohmann::json()) : nlohmann::json();
  const std::string reason = logger::likeliestReason(verdict);
  j["verdict_reason"] = reason.empty() ? nlohmann::json() : nlohmann::json(reason);
  j["verdict_kind"] = likeliestKind(verdict);
  return j;
}

wiring::InProcessOutcome SweepRunner::runExternal(const SweepRow& row, bool (*stop_requested)()) {
  namespace fs = std::filesystem;
  if (self_exe_.empty() || out_dir_.empty())
    throw RuntimeFault(
        "an external program's row runs through lagrange run; this sweep runner has no binary");
  const fs::path dir = fs::path(out_dir_) / "external" / ("row-" + std::to_string(row.index));
  // Never through a link planted as OUT/external (a shared sweep folder):
  // remove_all would follow it. Twice at most: finishing the sweep removes an
  // empty OUT/external/, which another shard may do between this one's mkdirs.
  for (int attempt = 0;; ++attempt) {
    try {
      util::makeOutputDirectory(dir.parent_path().string());
      fs::remove_all(dir);  // a link named row-N is removed itself, not followed
      util::makeOutputDirectory(dir.string());
      break;
    } catch (const lagrange::RuntimeFault&) {
      if (attempt > 0) throw;
    }
  }
  std::vector<std::string> args = {
      self_exe_, "run", plan_.spec.scenario_path, "--mode", "lockstep", "-q", "--out", dir.string()};
  for (const std::string& ov : row.overrides) args.insert(args.end(), {"--set", ov});
  const pid_t pid = wiring::spawnLogged(args, {(dir / "run.out").string()});
  int wstatus = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &wstatus, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) throw RuntimeFault(std::string("waitpid: ") + std::strerror(errno));
    if (stop_requested && stop_requested()) {
      kill(pid, SIGTERM);  // the launcher stops its processes
      waitpid(pid, &wstatus, 0);
      wiring::InProcessOutcome stopped;
      stopped.status = "interrupted";
      return stopped;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  wiring::InProcessOutcome o;
  nlohmann::json summary;
  try {
    summary = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  } catch (const std::exception&) {
    throw RuntimeFault("the external program's run left no summary.json (exit " +
                       std::to_string(WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus)) +
                       launcherError(dir / "run.out") + "); see " + dir.string());
  }
  o.status = summary.value("status", std::string("failed"));
  external_verdict_ = summary.value("verdict", nlohmann::json());
  const int exit_code = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
  // Stopped by a signal (Ctrl-C, scancel reaching the row's run directly
  // before this loop saw the shard's stop): run again on a restart. Stopped
  // by the launcher because a process died (exit 1; `failure` says which):
  // a row that failed, not one to run again, which would fail the same way.
  if (o.status == "interrupted")
    o.status =
        exit_code == kExitInterrupted || (stop_requested && stop_requested()) ? "interrupted" : "failed";
  const nlohmann::json& t = summary.at("tracking");
  if (!t.at("convergence_time").is_null())
    o.tracking.convergence_time = t.at("convergence_time").get<double>();
  // A non-finite number is null in summary.json (a run that blew up): NaN here.
  const auto number = [](const nlohmann::json& v) {
    return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  o.tracking.final_error = number(t.at("final_error"));
  o.tracking.max_error = number(t.at("max_error"));
  o.tracking.rms_last_second = number(t.at("rms_last_second"));
  // Why a run that did not complete stopped: the plant's last word.
  const nlohmann::json plant = summary.value("/processes/plant"_json_pointer, nlohmann::json::object());
  if (const auto f = summary.find("failure"); f != summary.end() && f->is_object())
    o.stop_message = f->contains("reason") ? f->value("reason", std::string()) + "; see " + dir.string()
                                           : "process '" + f->value("process", std::string("?")) + "' " +
                                                 f->value("how", std::string()) + "; see " + dir.string();
  else if (o.status != "completed")
    o.stop_message =
        plant.value("message", std::string()) + launcherError(dir / "run.out") + "; see " + dir.string();
  // Kept when it did not complete, or a process died after it did: its logs say why.
  if (o.status == "completed" && !summary.contains("failure")) fs::remove_all(dir);
  return o;
}

}  // namespace lagrange::tools
