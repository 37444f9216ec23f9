#include "tools/compare/compare_output.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "util/error.hpp"
#include "util/number_text.hpp"
#include "util/output_stream.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;

std::string number(double x) {
  if (!std::isfinite(x)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

std::string full(double x) { return std::isfinite(x) ? util::exactText(x) : ""; }

// The verdict's word and its likeliest reason, as the run's own block says them.
std::string verdictCell(const RunNumbers& n) {
  std::string cell = n.verdict.empty() ? "—" : n.verdict;
  if (!n.verdict_reason.empty()) cell += ": " + n.verdict_reason;
  std::string escaped;  // a table cell: a '|' would split it
  for (char c : cell) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
  return escaped;
}

std::string markdownRow(const RunNumbers& n, bool with_value) {
  std::string row = "| " + n.type + (with_value ? " | " + n.value.value_or("") : "") + " | " + n.status +
                    " | " + verdictCell(n) + " | " +
                    (n.convergence_time                 ? number(*n.convergence_time)
                     : n.status.rfind("failed", 0) == 0 ? "—"
                                                        : "not within the run") +
                    " | ";
  for (double x : {n.final_error, n.rms_last_second, n.max_torque, n.total_variation, n.energy})
    row += number(x) + " | ";
  return row.substr(0, row.size() - 1) + "\n";
}

std::string markdownHeader(const std::string& first) {
  return "| controller" + first +
         " | status | verdict | converged at [s] | final ‖q̃‖ [rad] | RMS ‖q̃‖, last second [rad] | max "
         "\\|τ\\| [N m] | "
         "torque total variation [N m] | ∫‖τ‖² dt [N² m² s] |\n"
         "| --- " +
         (first.empty() ? "" : "| --- ") + "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
}

// The number a sweep value plots at: a number, or the first of a list of
// numbers (a per-joint value with every joint alike); none otherwise.
std::optional<double> plotPosition(const std::string& value) {
  try {
    YAML::Node node = YAML::Load(value);
    if (node.IsSequence() && node.size() > 0) node = node[0];
    if (node.IsScalar()) return node.as<double>();
  } catch (const YAML::Exception&) {
  }
  return std::nullopt;
}

std::string relativeDir(const std::string& dir, const std::string& out_dir) {
  return fs::relative(fs::path(dir), fs::path(out_dir)).string();
}

}  // namespace

std::string writeComparison(const ComparisonTables& t, const std::string& out_dir) {
  std::string md = "# Comparison: " + t.scenario + "\n\n" + markdownHeader("");
  for (const RunNumbers& n : t.runs)
    if (!n.value) md += markdownRow(n, false);
  if (!t.sweep_key.empty()) {
    md += "\n## Sweep of " + t.sweep_key + "\n\n" + markdownHeader(" | " + t.sweep_key);
    for (const RunNumbers& n : t.runs)
      if (n.value) md += markdownRow(n, true);
  }
  util::OutputStream out_md(fs::path(out_dir) / "comparison.md");
  out_md << md;
  util::OutputStream csv(fs::path(out_dir) / "comparison.csv");
  csv << "controller,sweep_key,sweep_value,status,convergence_time,final_error,rms_last_second,max_abs_"
         "torque,"
         "torque_total_variation,control_energy,verdict,verdict_reason\n";
  for (const RunNumbers& n : t.runs) {
    csv << n.type << "," << (n.value ? t.sweep_key : "") << ",\"" << n.value.value_or("") << "\"," << n.status
        << "," << (n.convergence_time ? full(*n.convergence_time) : "");
    for (double x : {n.final_error, n.rms_last_second, n.max_torque, n.total_variation, n.energy})
      csv << "," << full(x);
    std::string reason;  // a CSV field: quoted, its quotes doubled
    for (char c : n.verdict_reason) reason += c == '"' ? std::string("\"\"") : std::string(1, c);
    csv << "," << n.verdict << ",\"" << reason << "\"\n";
  }
  if (!out_md.flush() || !csv.flush()) throw RuntimeFault("cannot write the comparison into " + out_dir);
  return md;
}

Plots drawComparisonPlots(const ComparisonTables& t, const std::string& out_dir) {
  std::vector<std::string> pngs, sections;
  // Every name in the script through gnuplotString: scenario and controller
  // names are the user's, a quote in one would end the string.
  const std::string title = "set title " + gnuplotString(t.scenario) + " noenhanced\n";
  std::string error = std::string(kGnuplotPreamble) +
                      "set terminal pngcairo size 1000,600\nset output 'error.png'\n" + title +
                      "set logscale y\nset format y '%.0e'\nset xlabel 't [s]'\n"
                      "set ylabel '||q - q_d|| [rad] (true angles)' noenhanced\nplot ";
  std::string torque = std::string(kGnuplotPreamble) + "set terminal pngcairo size 1000," +
                       std::to_string(250 * std::max(2, t.dof)) +
                       "\nset output 'torque.png'\nset multiplot layout " + std::to_string(t.dof) +
                       ",1 title " + gnuplotString(t.scenario + ": applied torques") + " noenhanced\n";
  std::vector<const RunNumbers*> nominal;
  for (const RunNumbers& n : t.runs)
    if (!n.value) nominal.push_back(&n);
  for (size_t i = 0; i < nominal.size(); ++i) {
    const std::string file = gnuplotString(relativeDir(nominal[i]->dir, out_dir) + "/series.csv");
    error += std::string(i ? ", \\\n     " : "") + file + " skip 1 using 1:2 with lines lw 2 title " +
             gnuplotString(nominal[i]->type) + " noenhanced";
  }
  error += "\n";
  for (int j = 0; j < t.dof; ++j) {
    torque += "set xlabel 't [s]'\nset ylabel 'tau_" + std::to_string(j + 1) + " [N m]' noenhanced\nplot ";
    for (size_t i = 0; i < nominal.size(); ++i)
      torque += std::string(i ? ", \\\n     " : "") +
                gnuplotString(relativeDir(nominal[i]->dir, out_dir) + "/series.csv") +
                " skip 1 using 1:" + std::to_string(3 + j) + " with lines title " +
                gnuplotString(nominal[i]->type) + " noenhanced";
    torque += "\n";
  }
  torque += "unset multiplot\n";
  pngs = {"error.png", "torque.png"};
  sections = {error, torque};

  // The sweep: RMS of ||q~|| over the last second against the value, one
  // file and one curve per controller; numbers only.
  if (!t.sweep_key.empty()) {
    bool numeric = true, positive = true, powers_of_two = true;
    std::vector<std::string> types;
    for (const RunNumbers& n : t.runs) {
      if (!n.value) {
        types.push_back(n.type);
        continue;
      }
      const std::optional<double> x = plotPosition(*n.value);
      numeric = numeric && x.has_value();
      positive = positive && x && *x > 0.0;
      powers_of_two = powers_of_two && positive && std::log2(*x) == std::round(std::log2(*x));
    }
    if (numeric) {
      std::string sweep = std::string(kGnuplotPreamble) +
                          "set terminal pngcairo size 1000,600\nset output 'sweep.png'\n" + title +
                          "set logscale y\nset format y '%.0e'\n" +
                          (powers_of_two ? "set logscale x 2\nset format x '2^{%L}'\n"
                           : positive    ? "set logscale x\nset format x '%.0e'\n"
                                         : "") +
                          "set xlabel " + gnuplotString(t.sweep_key) +
                          " noenhanced\n"
                          "set ylabel 'RMS ||q - q_d|| over the last second [rad]' noenhanced\nplot ";
      for (size_t i = 0; i < types.size(); ++i) {
        const std::string file = "sweep_" + types[i] + ".csv";
        util::OutputStream data(fs::path(out_dir) / file);
        data << "value,rms_last_second,final_error\n";
        for (const RunNumbers& n : t.runs)
          if (n.value && n.type == types[i])
            data << full(*plotPosition(*n.value)) << "," << full(n.rms_last_second) << ","
                 << full(n.final_error) << "\n";
        sweep += std::string(i ? ", \\\n     " : "") + gnuplotString(file) +
                 " skip 1 using 1:2 with linespoints lw 2 title " + gnuplotString(types[i]) + " noenhanced";
      }
      pngs.push_back("sweep.png");
      sections.push_back(sweep + "\n");
    }
  }
  util::OutputStream script(fs::path(out_dir) / "compare.gp");
  script << "# gnuplot script written by lagrange compare; run: cd THIS_DIR && gnuplot compare.gp\n";
  for (const std::string& s : sections) script << "\n" << s;
  if (!script.flush()) throw PlotError("cannot write " + out_dir + "/compare.gp");
  return drawPictures(out_dir, pngs, sections);
}

}  // namespace lagrange::tools
