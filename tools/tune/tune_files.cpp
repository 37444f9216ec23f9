#include "tools/tune/tune_files.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tools/report/plots.hpp"
#include "tools/tune/tune.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace lagrange::tools {

namespace fs = std::filesystem;

std::vector<double> flattened(const TuneGains& gains) {
  std::vector<double> out;
  for (const auto& g : gains) out.insert(out.end(), g.second.begin(), g.second.end());
  return out;
}

namespace {

nlohmann::json optionalNumber(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? nlohmann::json(*v) : nlohmann::json();
}
nlohmann::json finiteOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }
std::optional<double> numberOf(const nlohmann::json& v) {
  return v.is_number() ? std::optional<double>(v.get<double>()) : std::nullopt;
}

std::string csvNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

nlohmann::ordered_json evaluationJson(int index, SearchPhase phase, const TuneEvaluation& e,
                                      double torque_limit) {
  nlohmann::ordered_json j;
  j["index"] = index;
  j["phase"] = toString(phase);
  nlohmann::ordered_json gains = nlohmann::ordered_json::object();
  for (const auto& [name, values] : e.gains) gains[name] = values;
  j["gains"] = gains;
  j["value"] = e.value;
  j["feasible"] = e.feasible ? nlohmann::json(*e.feasible) : nlohmann::json();
  j["failed"] = e.failed.empty() ? nlohmann::json() : nlohmann::json(e.failed);
  j["status"] = e.status.empty() ? nlohmann::json() : nlohmann::json(e.status);
  j["convergence_time"] = optionalNumber(e.convergence_time);
  j["judged_to"] = optionalNumber(e.judged_to);
  j["late_error"] = e.judged_to ? finiteOrNull(e.late_error) : nlohmann::json();
  j["estimated_time"] = optionalNumber(e.estimated_time);
  j["final_error"] = finiteOrNull(e.final_error);
  j["peak_torque"] = finiteOrNull(e.peak_torque);
  j["torque_limit"] = torque_limit > 0.0 ? nlohmann::json(torque_limit) : nlohmann::json();
  j["margin"] = optionalNumber(e.margin);
  j["condition_holds"] = e.margin ? nlohmann::json(*e.margin > 0.0) : nlohmann::json();
  j["condition_lhs"] = optionalNumber(e.condition_lhs);
  j["sampled_verdict"] = e.sampled_verdict.empty() ? nlohmann::json() : nlohmann::json(e.sampled_verdict);
  j["sampled_why"] = e.sampled_why.empty() ? nlohmann::json() : nlohmann::json(e.sampled_why);
  nlohmann::json starts = nlohmann::json::array();
  for (const auto& t : e.start_times) starts.push_back(optionalNumber(t));
  j["start_times"] = e.sampled_verdict.empty() ? nlohmann::json() : starts;
  j["linearised_verdict"] =
      e.linearised_verdict.empty() ? nlohmann::json() : nlohmann::json(e.linearised_verdict);
  j["sufficient_rate"] = optionalNumber(e.sufficient_rate);
  j["wall_time"] = e.wall_time;
  j["times"] = {
      {"load", e.load_time}, {"run", e.run_time}, {"check", e.check_time}, {"linearised", e.linearised_time}};
  return j;
}

TuneEvaluation evaluationFromJson(const nlohmann::ordered_json& j) {
  try {
    TuneEvaluation e;
    for (const auto& [name, values] : j.at("gains").items())
      e.gains.emplace_back(name, values.get<std::vector<double>>());
    e.value = j.at("value").get<double>();
    if (j.at("feasible").is_boolean()) e.feasible = j.at("feasible").get<bool>();
    e.failed = j.at("failed").is_string() ? j.at("failed").get<std::string>() : "";
    e.status = j.at("status").is_string() ? j.at("status").get<std::string>() : "";
    e.convergence_time = numberOf(j.at("convergence_time"));
    e.judged_to = numberOf(j.value("judged_to", nlohmann::json()));  // (lines before 2026-12-07 have none)
    e.late_error = numberOf(j.value("late_error", nlohmann::json())).value_or(NAN);
    e.estimated_time = numberOf(j.value("estimated_time", nlohmann::json()));
    e.final_error = numberOf(j.at("final_error")).value_or(NAN);
    e.peak_torque = numberOf(j.at("peak_torque")).value_or(NAN);
    e.margin = numberOf(j.at("margin"));
    e.condition_lhs = numberOf(j.at("condition_lhs"));
    if (j.at("sampled_verdict").is_string()) e.sampled_verdict = j.at("sampled_verdict").get<std::string>();
    if (j.at("sampled_why").is_string()) e.sampled_why = j.at("sampled_why").get<std::string>();
    if (j.at("start_times").is_array())
      for (const auto& t : j.at("start_times")) e.start_times.push_back(numberOf(t));
    if (j.at("linearised_verdict").is_string())
      e.linearised_verdict = j.at("linearised_verdict").get<std::string>();
    e.sufficient_rate = numberOf(j.at("sufficient_rate"));
    e.wall_time = j.at("wall_time").get<double>();
    if (j.contains("times")) {  // (older lines have none)
      const auto& t = j.at("times");
      e.load_time = t.value("load", 0.0);
      e.run_time = t.value("run", 0.0);
      e.check_time = t.value("check", 0.0);
      e.linearised_time = t.value("linearised", 0.0);
    }
    return e;
  } catch (const nlohmann::json::exception& error) {
    throw BadInput(std::string("a line of tune.jsonl is not an evaluation (") + error.what() +
                   "); expected the lines lagrange tune writes");
  }
}

std::vector<nlohmann::ordered_json> readEvaluationLines(const std::string& dir) {
  // In the file's order: a line's gains in the declaration's order, as the
  // search's points are.
  std::vector<nlohmann::ordered_json> out;
  std::ifstream in(fs::path(dir) / "tune.jsonl");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    try {
      out.push_back(nlohmann::ordered_json::parse(line));
    } catch (const nlohmann::json::exception&) {
      if (in.peek() == EOF) break;  // torn by an interrupt while it was written: made again
      throw BadInput(fs::path(dir).append("tune.jsonl").string() + " holds a line that is not JSON (line " +
                     std::to_string(out.size() + 1) + "); expected the lines lagrange tune writes");
    }
  }
  return out;
}

std::map<std::vector<double>, TuneEvaluation> readEvaluations(const std::string& dir, SearchPhase which) {
  std::map<std::vector<double>, TuneEvaluation> out;
  const bool confirm = which == SearchPhase::kConfirm;
  for (const nlohmann::ordered_json& line : readEvaluationLines(dir)) {
    if ((line.value("phase", "") == toString(SearchPhase::kConfirm)) != confirm) continue;
    TuneEvaluation e = evaluationFromJson(line);
    out.emplace(flattened(e.gains), std::move(e));
  }
  return out;
}

void appendEvaluation(const std::string& dir, const nlohmann::ordered_json& line) {
  const std::string path = (fs::path(dir) / "tune.jsonl").string();
  const int fd = util::openOutputFileToAppend(path);
  try {
    util::writeAll(fd, line.dump() + "\n", path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

nlohmann::ordered_json tuneArguments(const TuneProblem& p, unsigned seed, double span_decades, int global) {
  nlohmann::ordered_json a;
  a["scenario"] = fs::absolute(p.scenario_path).lexically_normal().string();
  a["overrides"] = p.overrides;
  a["controller"] = p.input.controller.type;
  a["seed"] = seed;
  a["span"] = span_decades;
  a["global"] = global;  // 0: the default, 10 (n + 1)
  a["require_condition"] = p.require_condition;
  // The objective's cut (a folder of a tune before it is not resumed with it).
  a["cut"] = p.cut_factor > 0.0 ? nlohmann::json(p.cut_factor) : nlohmann::json();
  nlohmann::json variables = nlohmann::json::array();
  for (const SearchVariable& v : p.variables) variables.push_back({v.label, v.lower, v.upper, v.start});
  a["variables"] = variables;
  return a;
}

std::string olderObjectiveText(const std::string& dir, const std::string& kind) {
  return dir + " holds a " + kind +
         " of an older lagrange, whose objective judged every run to its end (this one stops a run once it "
         "cannot beat the best: docs/tuning.md)";
}

nlohmann::ordered_json tuneBudget(int evaluations, double minutes) {
  const int n = evaluations > 0 ? evaluations : minutes > 0.0 ? 0 : kDefaultEvaluations;
  nlohmann::ordered_json b;
  b["evaluations"] = n > 0 ? nlohmann::json(n) : nlohmann::json();
  b["minutes"] = minutes > 0.0 ? nlohmann::json(minutes) : nlohmann::json();
  return b;
}

void prepareTuneDir(const std::string& dir, const nlohmann::ordered_json& arguments) {
  util::makeOutputDirectories(dir);
  const fs::path jsonl = fs::path(dir) / "tune.jsonl";
  std::error_code ec;
  if (!fs::exists(jsonl, ec) || fs::file_size(jsonl, ec) == 0) return;
  nlohmann::json before;
  try {
    before = nlohmann::json::parse(std::ifstream(fs::path(dir) / "tune.json")).at("arguments");
  } catch (const std::exception&) {
    throw BadInput(dir +
                   " holds a tune.jsonl without a readable tune.json: not a tune this command can "
                   "resume; expected an empty DIR or one a lagrange tune wrote");
  }
  for (const auto& [key, value] : arguments.items()) {
    if (key == "cut" && !before.contains(key)) {
      if (value.is_null()) continue;  // --full-runs: the objective that tune was made with
      throw BadInput(olderObjectiveText(dir, "tune") +
                     "; its evaluations do not resume this tune: expected another --out, or --full-runs to "
                     "resume it");
    }
    if (key == "cut" && before.at(key) != nlohmann::json(value))
      throw BadInput(dir + " holds a tune made " + (value.is_null() ? "without" : "with") +
                     " --full-runs (arguments.cut " + before.at(key).dump() +
                     "); a resume judges the runs as that tune did: expected " +
                     (value.is_null() ? "no --full-runs" : "--full-runs") + ", or another --out");
    if (!before.contains(key) || before.at(key) != nlohmann::json(value))
      throw BadInput(
          dir + " holds a tune with other arguments (" + key + ": " +
          (before.contains(key) ? before.at(key).dump() : std::string("none")) + ", now " +
          nlohmann::json(value).dump() +
          "); a resume repeats the same scenario, --set, --seed, --span, --global, --require-condition and "
          "--full-runs; "
          "expected those, or another --out");
  }
}

void writeTuneJson(const std::string& dir, const nlohmann::ordered_json& arguments,
                   const nlohmann::ordered_json& result) {
  nlohmann::ordered_json j;
  j["arguments"] = arguments;
  j["result"] = result;
  util::writeOutputFile((fs::path(dir) / "tune.json").string(), j.dump(2) + "\n");
}

void writeTunedYaml(const std::string& dir, const TuneProblem& p, const TuneGains& gains) {
  const fs::path base = fs::absolute(p.scenario_path).lexically_normal();
  const fs::path relative = base.lexically_relative(fs::absolute(dir).lexically_normal());
  YAML::Node root;
  root["extends"] = relative.empty() ? base.string() : relative.string();
  // The user's --set, as keys: the tuned gains were found with them.
  for (const std::string& o : p.overrides) {
    const size_t eq = o.find('=');
    std::vector<std::string> parts;
    std::stringstream key(o.substr(0, eq));
    for (std::string part; std::getline(key, part, '.');) parts.push_back(part);
    std::vector<YAML::Node> chain = {root};
    for (size_t i = 0; i + 1 < parts.size(); ++i) chain.push_back(chain.back()[parts[i]]);
    chain.back()[parts.back()] = YAML::Load(o.substr(eq + 1));
  }
  YAML::Node controller = root["controller"];
  controller["type"] = p.input.controller.type;
  // A chain's stages whole, as extends replaces a list: their other keys kept.
  if (const std::string stages = stagesYaml(p.input, gains); !stages.empty())
    controller["stages"] = YAML::Load(stages);
  for (const auto& [name, values] : gains) {
    if (name.rfind("stages[", 0) == 0) continue;  // in controller.stages above
    if (values.size() == 1) {
      controller[name] = values.front();
    } else {
      YAML::Node list(YAML::NodeType::Sequence);
      for (double v : values) list.push_back(v);
      list.SetStyle(YAML::EmitterStyle::Flow);
      controller[name] = list;
    }
  }
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << root;
  util::writeOutputFile((fs::path(dir) / "tuned.yaml").string(),
                        "# Written by lagrange tune (docs/tuning.md): the input scenario with the best gains "
                        "found.\n# Run it as it is: lagrange run " +
                            (fs::path(dir) / "tuned.yaml").string() + "\n" + out.c_str() + "\n");
}

std::string drawFront(const std::string& dir, const std::vector<nlohmann::ordered_json>& lines) {
  std::string csv = "convergence_time,peak_torque,margin,input,feasible\n";
  int points = 0;
  bool margins = false;
  double limit = 0.0;  // the torque limit the candidates were held to, drawn as a line
  for (const nlohmann::ordered_json& l : lines) {
    if (l.contains("torque_limit") && l["torque_limit"].is_number()) limit = l["torque_limit"].get<double>();
    if (!l.contains("convergence_time") || !l["convergence_time"].is_number() || !l.contains("peak_torque") ||
        !l["peak_torque"].is_number())
      continue;
    const std::string failed =
        l.contains("failed") && l["failed"].is_string() ? l["failed"].get<std::string>() : "";
    if (failed.rfind("metric", 0) == 0 || failed.rfind("diverged", 0) == 0) continue;
    margins = margins || l["margin"].is_number();
    csv += csvNumber(l["convergence_time"].get<double>()) + "," + csvNumber(l["peak_torque"].get<double>()) +
           "," + (l["margin"].is_number() ? csvNumber(l["margin"].get<double>()) : "NaN") + "," +
           (l.value("phase", "") == "start" ? "1" : "0") + "," + (l["feasible"] == true ? "1" : "0") + "\n";
    ++points;
  }
  util::writeOutputFile((fs::path(dir) / "front.csv").string(), csv);
  if (points == 0) return "front.png: no candidate met the metric from the initial state";
  std::string script = std::string(kGnuplotPreamble) +
                       "set terminal pngcairo size 1000,650\nset output 'front.png'\n"
                       "set title 'lagrange tune: convergence time against peak torque' noenhanced\n"
                       "set xlabel 'peak |torque| [N m]'\nset ylabel 'convergence time [s]'\n"
                       "set key top right\n";
  if (limit > 0.0)
    script += "set arrow from " + csvNumber(limit) + ", graph 0 to " + csvNumber(limit) +
              ", graph 1 nohead dt 2 lc rgb 'red'\nset label 'torque limit' at " + csvNumber(limit) +
              ", graph 0.97 right offset -0.5,0 tc rgb 'red'\n";
  script += margins ? "set cblabel 'eq. (12) margin'\nset palette rgbformulae 33,13,10\n"
                      "plot 'front.csv' skip 1 using 2:1:3 with points pt 7 ps 1.2 palette title "
                      "'candidates, coloured by eq. (12) margin' , "
                      "'' skip 1 using 2:($5 > 0 ? $1 : NaN) with points pt 6 ps 2 lc rgb 'black' title "
                      "'passed every check', "
                      "'' skip 1 using 2:($4 > 0 ? $1 : NaN) with points pt 5 ps 2.5 lc rgb 'red' title "
                      "'the input gains'\n"
                    : "plot 'front.csv' skip 1 using 2:1 with points pt 7 ps 1.2 lc rgb 'gray40' title "
                      "'candidates', "
                      "'' skip 1 using 2:($5 > 0 ? $1 : NaN) with points pt 6 ps 2 lc rgb 'black' title "
                      "'passed every check', "
                      "'' skip 1 using 2:($4 > 0 ? $1 : NaN) with points pt 5 ps 2.5 lc rgb 'red' title "
                      "'the input gains'\n";
  try {
    const Plots plots = drawPictures(dir, {"front.png"}, {script});
    if (!plots.failed.empty()) return "front.png: gnuplot failed (see " + plots.log + ")";
  } catch (const PlotError& e) {
    return std::string("front.png: ") + e.what();
  }
  return "";
}

}  // namespace lagrange::tools
