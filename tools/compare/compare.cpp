#include "tools/compare/compare.hpp"

#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "config/controller_params.hpp"
#include "config/scenario.hpp"
#include "config/yaml_reader.hpp"
#include "logger/verdict.hpp"
#include "logs/log_reader.hpp"
#include "logs/out_dir_lock.hpp"
#include "model/reference.hpp"
#include "tools/command_error.hpp"
#include "tools/compare/compare_output.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "util/error.hpp"
#include "util/jobs.hpp"
#include "util/output_stream.hpp"
#include "util/terminal_text.hpp"
#include "wiring/spawn_logged.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;
using config::ConfigError;
using config::flowYaml;

// The override that gives a run `type` with its compare section, or none when
// `type` is the scenario's own controller and its compare section is empty
// (or absent): the controller section as it stands.
std::optional<std::string> controllerOverride(const config::Scenario& s, const std::string& type,
                                              const std::string& path) {
  if (s.compare)
    for (const auto& [t, keys] : s.compare->controllers)
      if (t == type) {
        YAML::Node section = YAML::Load(keys);
        if (!section.IsMap() || section.size() == 0) {
          if (type == s.controller.type) return std::nullopt;
          section = YAML::Node(YAML::NodeType::Map);
        }
        if (!section["type"]) section["type"] = type;  // else the name is a row label
        return "controller=" + flowYaml(section);
      }
  if (type == s.controller.type) return std::nullopt;
  throw ConfigError("config: " + path + ": compare.controllers has no section for '" + type +
                    "'; expected compare.controllers." + type +
                    " with its keys (or the scenario's own controller.type; docs/comparison.md)");
}

// A row's controller type: its compare.controllers entry's `type` when it has
// one (the name is then a label, e.g. one external program of several), else its name.
std::string typeOf(const config::Scenario& s, const std::string& name) {
  if (s.compare)
    for (const auto& [t, keys] : s.compare->controllers)
      if (t == name) {
        const YAML::Node section = YAML::Load(keys);
        if (section.IsMap() && section["type"]) return section["type"].Scalar();
      }
  return name;
}

struct Sweep {
  std::string key;
  std::vector<std::string> values;  // YAML text
};

std::optional<Sweep> sweepOf(const CompareOptions& o, const config::Scenario& s) {
  if (o.sweep.empty()) {
    if (!s.compare || s.compare->sweep_key.empty()) return std::nullopt;
    return Sweep{s.compare->sweep_key, s.compare->sweep_values};
  }
  const size_t eq = o.sweep.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("--sweep: expected KEY=[V1, V2, ...], got '" + o.sweep + "'");
  Sweep sweep{o.sweep.substr(0, eq), {}};
  YAML::Node list;
  try {
    list = YAML::Load(o.sweep.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw ConfigError("--sweep " + sweep.key + ": malformed YAML: " + e.msg);
  }
  if (!list.IsSequence() || list.size() == 0)
    throw ConfigError("--sweep " + sweep.key +
                      ": expected a YAML list of at least one value, e.g. [4096, 65536]");
  for (const YAML::Node& v : list) sweep.values.push_back(flowYaml(v));
  return sweep;
}

// A directory name for a sweep value: its index, then its characters that are
// safe in a path.
std::string valueDir(size_t index, const std::string& value) {
  std::string safe;
  for (char c : value) safe += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
  return "value" + std::to_string(index) + "_" + safe.substr(0, 40);
}

// Starts `self run CONFIG --mode inproc -q --out DIR --set ...`, output in DIR/compare.log.
pid_t startRun(const CompareOptions& o, const CompareRun& run) {
  std::vector<std::string> args = {o.self_exe, "run", o.config_path, "-q", "--out", run.dir};  // mode: --set
  for (const std::string& ov : run.overrides) args.insert(args.end(), {"--set", ov});
  return wiring::spawnLogged(args, {(fs::path(run.dir) / "compare.log").string()});
}

// Runs every run, at most `jobs` at a time; returns each one's exit status.
std::vector<int> runAll(const CompareOptions& o, const std::vector<CompareRun>& runs) {
  const int jobs = util::jobsOrCores(o.jobs);
  std::vector<int> status(runs.size(), -1);
  std::map<pid_t, size_t> running;
  size_t next = 0, done = 0;
  while (done < runs.size()) {
    while (next < runs.size() && static_cast<int>(running.size()) < jobs) {
      fs::remove_all(runs[next].dir);
      fs::create_directories(runs[next].dir);
      running[startRun(o, runs[next])] = next;
      ++next;
    }
    int wstatus = 0;
    const pid_t pid = waitpid(-1, &wstatus, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw RuntimeFault(std::string("waitpid: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    status[it->second] = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
    running.erase(it);
    ++done;
    if (!o.quiet)
      std::cout << "lagrange compare: " << done << " of " << runs.size() << " runs done\n" << std::flush;
  }
  return status;
}

// The numbers of one finished run, from its summary.json.
RunNumbers numbersOf(const CompareRun& run, int exit_status) {
  RunNumbers n;
  n.type = run.type;
  n.value = run.value;
  n.dir = run.dir;
  std::ifstream in(fs::path(run.dir) / "summary.json");
  if (!in) {
    n.status = "failed (exit " + std::to_string(exit_status) + "; see " + run.dir + "/compare.log)";
    return n;
  }
  const nlohmann::json j = nlohmann::json::parse(in);
  n.status = j.at("status").get<std::string>();
  // The run's verdict as its summary has it (logger/verdict.hpp), never decided here again.
  if (const auto v = j.find("verdict"); v != j.end() && v->is_object()) {
    n.verdict = v->value("tracking", std::string());
    n.verdict_reason = logger::likeliestReason(*v);
  }
  // A process that died: the launcher says which in summary.json's
  // `failure`; an older or killed launcher left only its exit code.
  if (const auto f = j.find("failure"); f != j.end() && f->is_object() && n.status == "failed") {
    n.failure = "process '" + f->value("process", std::string("?")) + "' " + f->value("how", std::string()) +
                "; see " + f->value("log", run.dir);
  } else if (exit_status != kExitOk && n.status == "interrupted") {
    n.status = "failed";
    n.failure =
        "lagrange run exited with code " + std::to_string(exit_status) + "; see " + run.dir + "/compare.log";
  }
  if (n.status == "failed") return n;  // the numbers of a run cut short are no result: left blank
  // null where a run blew up (summary.json writes a non-finite number so)
  const auto number = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : std::nan(""); };
  const auto& t = j.at("tracking");
  if (!t.at("convergence_time").is_null()) n.convergence_time = t.at("convergence_time").get<double>();
  n.final_error = number(t.at("final_error"));
  n.rms_last_second = number(t.at("rms_last_second"));
  const auto& torque = j.at("torque");
  n.max_torque = number(torque.at("max_abs"));
  n.total_variation = number(torque.at("total_variation"));
  n.energy = number(torque.at("energy"));
  return n;
}

// DIR/series.csv of a nominal run: t, ||q~|| from the true angles (against
// the base scenario's reference, which is the run's), and the applied torque
// per joint -- what the overlay plots draw.
void writeSeries(const CompareRun& run, const config::Scenario& s) {
  const model::Reference reference(s.reference);
  util::OutputStream out(fs::path(run.dir) / "series.csv");
  out << "t,error_norm";
  for (int j = 0; j < s.dof(); ++j) out << ",tau" << j;
  out << "\n";
  std::set<int64_t> seen;
  const std::string log = (fs::path(run.dir) / "run.lcm").string();
  if (!fs::exists(log)) return;
  logs::readLog(log, [&](const lcm::LogEvent& ev) {
    if (ev.channel != transport::kPlantTruth) return;
    lagrange::plant_truth_t m;
    if (!logs::decodeEvent(ev, m) || !seen.insert(m.header.tick).second) return;
    const Eigen::VectorXd q = transport::toEigen(m.q);
    char line[64];
    std::snprintf(line, sizeof line, "%.9g,%.9g", m.header.sim_time,
                  (q - reference.evaluate(m.header.sim_time, 0).q()).norm());
    out << line;
    for (double tau : m.tau_applied) {
      std::snprintf(line, sizeof line, ",%.9g", tau);
      out << line;
    }
    out << "\n";
  });
}

}  // namespace

ComparisonPlan planComparison(const CompareOptions& o) {
  ComparisonPlan plan;
  plan.base = config::loadScenario(o.config_path, o.overrides);
  const config::Scenario& base = plan.base;
  std::vector<std::string> types = o.controllers;
  if (types.empty() && base.compare)
    for (const auto& [type, keys] : base.compare->controllers) types.push_back(type);
  if (types.empty())
    throw ConfigError("config: " + o.config_path +
                      ": no controllers to compare; expected --controllers A,B,... or a compare.controllers "
                      "section (docs/comparison.md)");
  std::set<std::string> unique;
  const std::vector<std::string> known = config::controllerTypes();
  for (const std::string& type : types) {
    if (!unique.insert(type).second) throw ConfigError("--controllers: '" + type + "' is named twice");
    if (std::find(known.begin(), known.end(), typeOf(base, type)) == known.end()) {
      const std::string list = config::controllerTypeList();
      throw ConfigError(
          (o.controllers.empty() ? "config: " + o.config_path + ": compare.controllers" : "--controllers") +
          ": unknown controller type '" + type + "'; expected: " + list);
    }
  }
  const std::optional<Sweep> sweep = sweepOf(o, base);
  if (sweep) plan.sweep_key = sweep->key;
  std::vector<CompareRun>& runs = plan.runs;
  for (const std::string& type : types) {
    // In process, as fast as the machine allows; an external program in
    // lockstep, its own process over LCM (the same loop, bit for bit).
    const bool external = typeOf(base, type) == "external" || base.plant.external();
    std::vector<std::string> overrides = {external ? "mode=lockstep" : "mode=inproc"};
    if (const auto controller = controllerOverride(base, type, o.config_path))
      overrides.push_back(*controller);
    overrides.insert(overrides.end(), o.overrides.begin(), o.overrides.end());
    const fs::path dir = fs::path(o.out_dir) / "runs" / type;
    try {  // its section, checked before anything runs
      config::loadScenario(o.config_path, overrides);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string(e.what()) + " (the controller section of " + type +
                        (base.compare ? ": compare.controllers." + type : std::string()) + ")");
    }
    runs.push_back({type, std::nullopt, overrides, dir.string()});
    if (!sweep) continue;
    for (size_t i = 0; i < sweep->values.size(); ++i) {
      std::vector<std::string> swept = overrides;
      swept.push_back(sweep->key + "=" + sweep->values[i]);
      try {
        config::loadScenario(o.config_path, swept);
      } catch (const ConfigError& e) {
        throw ConfigError(std::string(e.what()) + " (the sweep of " + sweep->key + ", value " +
                          sweep->values[i] + ", with controller " + type + ")");
      }
      runs.push_back({type, sweep->values[i], swept, (dir / valueDir(i, sweep->values[i])).string()});
    }
  }
  return plan;
}

int runComparison(const CompareOptions& o) {
  ComparisonPlan plan;
  try {
    plan = planComparison(o);
  } catch (const std::exception& e) {
    return failWith("lagrange compare", e);
  }
  // One comparison per directory, like one run (logs/out_dir_lock.hpp):
  // two would run into the same runs/TYPE and write one comparison.md.
  std::optional<logs::OutDirLock> lock;
  try {
    fs::create_directories(o.out_dir);
    lock.emplace(o.out_dir, "lagrange compare");
  } catch (const std::exception& e) {
    return failWith("lagrange compare", e);
  }
  try {
    const std::vector<CompareRun>& runs = plan.runs;
    const std::vector<int> status = runAll(o, runs);
    std::vector<RunNumbers> numbers;
    for (size_t i = 0; i < runs.size(); ++i) {
      numbers.push_back(numbersOf(runs[i], status[i]));
      if (!runs[i].value) writeSeries(runs[i], plan.base);
    }
    ComparisonTables tables{plan.base.name, plan.base.dof(), plan.sweep_key, numbers};
    const std::string table = writeComparison(tables, o.out_dir);
    if (!o.quiet) std::cout << util::terminalSafeLines(table);  // names and reasons from files
    const Plots plots = drawComparisonPlots(tables, o.out_dir);
    if (!o.quiet)
      for (const std::string& png : plots.written) std::cout << "lagrange compare: wrote " << png << "\n";
    for (const std::string& png : plots.failed)
      std::cerr << "lagrange compare: gnuplot could not draw " << png << " (see " << plots.log << ")\n";
    bool failed = false;
    for (const RunNumbers& n : numbers) {
      if (n.status.rfind("failed", 0) != 0) continue;
      failed = true;
      if (!n.failure.empty())
        std::cerr << util::terminalSafeLines("lagrange compare: " + n.type +
                                             (n.value ? " at " + plan.sweep_key + " = " + *n.value : "") +
                                             " failed: " + n.failure)
                  << "\n";
    }
    return failed ? kExitFailed : kExitOk;
  } catch (const std::exception& e) {
    return failWith("lagrange compare", e);
  }
}

}  // namespace lagrange::tools
