// The gnuplot script of `lagrange report` (plots.hpp): which pictures the
// CSV files allow, and how each is drawn.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "tools/report/csv_export.hpp"
#include "tools/report/csv_rows.hpp"
#include "tools/report/plots.hpp"
#include "tools/report/signal_range.hpp"
#include "tools/report/tracking_table.hpp"
#include "transport/channels.hpp"
#include "util/number_text.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;

// The 1-based gnuplot column of each field of DIR/CHANNEL.csv; empty if there is no such file.
std::map<std::string, int> columnsOf(const std::string& dir, const std::string& channel) {
  std::ifstream in(fs::path(dir) / (channel + ".csv"));
  std::string header;
  std::map<std::string, int> columns;
  if (!std::getline(in, header)) return columns;
  std::istringstream fields(header);
  std::string name;
  for (int i = 1; std::getline(fields, name, ','); ++i) columns[name] = i;
  return columns;
}

std::string quoted(const std::string& text) { return gnuplotString(text); }

// The CSV column of element i (0-based here) of a field: numbered from 1 there.
std::string indexed(const std::string& field, int i) { return field + "[" + std::to_string(i + 1) + "]"; }

// "column(A)**2 + column(B)**2 + ..." under a square root: the norm of a vector field.
std::string normOf(const std::map<std::string, int>& cols, const std::string& field, int n) {
  std::string sum;
  for (int j = 0; j < n; ++j) {
    const auto it = cols.find(indexed(field, j));
    if (it == cols.end()) return "";
    sum += (j ? " + " : "") + std::string("column(") + std::to_string(it->second) + ")**2";
  }
  return "sqrt(" + sum + ")";
}

// One line of a plot command: FILE using TIME:EXPR.
std::string series(const std::string& channel, const std::string& expr, const std::string& title,
                   const std::string& style = "lw 1.5") {
  return quoted(channel + ".csv") + " skip 1 using 2:(" + expr + ") with lines " + style + " title " +
         quoted(title);
}

// A number for a label: four significant digits ("0.915", "-288.4", "1.5e+06").
std::string shortText(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

std::string column(const std::map<std::string, int>& cols, const std::string& name) {
  const auto it = cols.find(name);
  return it == cols.end() ? "" : "column(" + std::to_string(it->second) + ")";
}

// The gnuplot text of one PNG, self-contained after the preamble.
struct Section {
  std::string png;
  std::string text;
};

class ScriptBuilder {
 public:
  explicit ScriptBuilder(const PlotSpec& spec) : spec_(spec) {
    truth_ = columnsOf(spec.dir, transport::kPlantTruth);
    command_ = columnsOf(spec.dir, transport::kControlCommand);
    actuator_ = columnsOf(spec.dir, transport::kActuatorState);
    motor_ = columnsOf(spec.dir, transport::kPlantMotor);
    timing_ = columnsOf(spec.dir, kTimingChannel);
    tracking_ = columnsOf(spec.dir, kTrackingChannel);
    // The transient ends, for the plots' clipped ranges, when the run
    // converged (if in its first half), else after a tenth of the run.
    const double end = spec.end_time;
    late_from_ =
        spec.convergence_time && *spec.convergence_time <= end / 2 ? *spec.convergence_time : end / 10;
  }

  std::vector<Section> build() {
    trackingError();
    jointErrors();
    chainError();
    joints();
    velocities();
    torques();
    filterStates();
    actuatorStates();
    motors();
    timing();
    return std::move(sections_);
  }

 private:
  // Starts a PNG of `panels` stacked plots.
  std::ostringstream& begin(const std::string& png, const std::string& what, int panels = 1) {
    sections_.push_back({png, ""});
    out_.str("");
    const int height = panels == 1 ? 600 : std::max(600, 260 * panels);
    out_ << "set output " << quoted(png) << "\nset terminal pngcairo size 1100," << height
         << " noenhanced font \"DejaVu Sans,11\"\n";
    if (panels > 1)
      out_ << "set multiplot layout " << panels << ",1 title " << quoted(spec_.title + ": " + what) << "\n";
    else
      out_ << "set title " << quoted(spec_.title + ": " + what) << "\n";
    return out_;
  }
  void end() {
    out_ << "unset multiplot\nunset output\nreset\n";
    sections_.back().text = out_.str();
  }

  // " (panda_joint1)" for joint j of a robot with named joints; "" for the
  // planar chain, whose names are its numbers.
  std::string named(int j) const {
    if (j >= static_cast<int>(spec_.joint_names.size())) return "";
    const std::string& name = spec_.joint_names[j];
    return name == "joint" + std::to_string(j + 1) ? "" : " (" + name + ")";
  }

  // The error the run is judged by: the truth against the reference
  // (TRACKING.csv, as summary.json); without the scenario, the controller's view.
  void trackingError() {
    const bool truth = !tracking_.empty();
    const std::string norm =
        truth ? column(tracking_, "q_error_norm") : normOf(command_, "q_error", spec_.dof);
    if (norm.empty()) return;
    auto& o = begin("tracking_error.png", "tracking error norm (log scale)");
    o << "set logscale y\nset format y \"1e%T\"\nset xlabel \"time t [s]\"\n"
         "set ylabel \"‖q~‖ = ‖q − q_d‖ [rad]\"\n";
    convergenceMarker(o);
    o << "plot "
      << (truth ? series(kTrackingChannel, positive(norm), "‖q − q_d‖ (PLANT_TRUTH against the reference)",
                         "lw 2 lc rgb \"#1f77b4\"")
                : series(transport::kControlCommand, positive(norm),
                         "‖q~‖ (CONTROL_COMMAND.q_error, the controller's view)", "lw 2 lc rgb \"#1f77b4\""));
    toleranceLine(o);
    o << "\n";
    end();
  }

  // |q_j − q_d,j| per joint, all in one log-scale panel, with the tolerance.
  void jointErrors() {
    if (tracking_.empty()) return;
    auto& o = begin("joint_errors.png", "tracking error per joint |q_j − q_d,j| (log scale)");
    o << "set logscale y\nset format y \"1e%T\"\nset xlabel \"time t [s]\"\n"
         "set ylabel \"|q~_j| [rad]\"\n";
    convergenceMarker(o);
    o << "plot ";
    for (int j = 0; j < spec_.dof; ++j)
      o << (j ? ", " : "")
        << series(kTrackingChannel, positive("abs(" + column(tracking_, indexed("q_error", j)) + ")"),
                  "|q~" + std::to_string(j + 1) + "|" + named(j));
    toleranceLine(o);
    o << "\n";
    end();
  }

  // A log scale takes no zero: an exact zero is left out rather than warned about.
  static std::string positive(const std::string& expr) { return "(" + expr + ") > 0 ? (" + expr + ") : NaN"; }

  void toleranceLine(std::ostream& o) const {
    if (spec_.tolerance > 0)
      o << ", " << spec_.tolerance << " with lines dt 2 lw 1.5 lc rgb \"gray30\" title "
        << quoted("metrics.tolerance = " + util::exactText(spec_.tolerance) + " rad");
  }

  // The convergence time as summary.json has it (a vertical line), or, for a
  // run that did not converge, a word saying so; nothing when unknown.
  void convergenceMarker(std::ostream& o) const {
    if (spec_.tolerance <= 0 || tracking_.empty()) return;
    if (!spec_.convergence_time) {
      o << "set label " << quoted("not within the tolerance at the end of the run")
        << " at graph 0.5, graph 0.95 center textcolor rgb \"#d62728\"\n";
      return;
    }
    const double t = *spec_.convergence_time;
    const bool right_half = spec_.end_time > 0 && t > 0.6 * spec_.end_time;
    o << "set arrow from " << util::exactText(t) << ", graph 0 to " << util::exactText(t)
      << ", graph 1 nohead dt 3 lw 1.5 lc rgb \"#2ca02c\"\n"
      << "set style textbox opaque noborder\nset label " << quoted("converged at t = " + shortText(t) + " s")
      << " at " << util::exactText(t) << ", graph 0.04 "
      << (right_half ? "right offset -0.5,0" : "left offset 0.5,0")
      << " boxed front textcolor rgb \"#2ca02c\"\n";
  }

  void chainError() {
    if (spec_.chain_order == 0 || command_.empty()) return;
    auto& o = begin("chain_error.png", "actuator-chain errors ‖ξ~_i‖ = ‖ξ_i − ξ_i*‖ (log scale)");
    o << "set logscale y\nset format y \"1e%T\"\nset xlabel \"time t [s]\"\n"
         "set ylabel \"‖ξ~_i‖ [N m / s^(i-1)]\"\nplot ";
    for (int i = 0; i < spec_.chain_order; ++i) {
      const std::string norm = normOf(command_, indexed("xi_error", i), spec_.dof);
      if (norm.empty()) continue;
      o << (i ? ", " : "") << series(transport::kControlCommand, norm, "stage i = " + std::to_string(i + 1));
    }
    o << "\n";
    end();
  }

  void joints() {
    const auto& q = truth_.empty() ? columnsOf(spec_.dir, transport::kPlantPosition) : truth_;
    const char* q_channel = truth_.empty() ? transport::kPlantPosition : transport::kPlantTruth;
    if (q.empty() && command_.empty()) return;
    auto& o = begin("joints.png", "joint angles q and references q_d", spec_.dof);
    for (int j = 0; j < spec_.dof; ++j) {
      o << "set xlabel \"time t [s]\"\nset ylabel "
        << quoted("q" + std::to_string(j + 1) + named(j) + " [rad]") << "\nplot ";
      std::string sep;
      if (const std::string c = column(q, indexed("q", j)); !c.empty())
        o << series(q_channel, c, "q" + std::to_string(j + 1) + " (" + q_channel + ")", "lw 2"), sep = ", ";
      if (const std::string c = column(command_, indexed("q_desired", j)); !c.empty())
        o << sep
          << series(transport::kControlCommand, c, "q_d" + std::to_string(j + 1) + " (reference)",
                    "lw 1.5 dt 2");
      o << "\n";
    }
    end();
  }

  // q' per joint against q_d' (TRACKING.csv), with a URDF's velocity limit.
  void velocities() {
    if (column(truth_, indexed("qdot", 0)).empty()) return;
    auto& o = begin("velocities.png", "joint rates q' and reference rates q_d'", spec_.dof);
    const std::string truth_csv =
        (std::filesystem::path(spec_.dir) / (std::string(transport::kPlantTruth) + ".csv")).string();
    o << "set style textbox opaque noborder\n";
    for (int j = 0; j < spec_.dof; ++j) {
      const std::string n = std::to_string(j + 1);
      const bool limited =
          j < static_cast<int>(spec_.velocity_limits.size()) && std::isfinite(spec_.velocity_limits[j]);
      o << "unset label\nset yrange [*:*]\n";
      // A start-up burst would flatten the rest: the range is clipped to the
      // rates after it (and the limit), and the panel says what it cut.
      const SignalRange range = signalRange(truth_csv, {indexed("qdot", j)}, late_from_);
      if (late_from_ > 0 && dominatedByStart(range)) {
        auto [lo, hi] = lateWindow(range);
        if (limited)
          lo = std::min(lo, -1.1 * spec_.velocity_limits[j]),
          hi = std::max(hi, 1.1 * spec_.velocity_limits[j]);
        if (range.hi - range.lo > 3.0 * (hi - lo))
          o << "set yrange [" << util::exactText(lo) << ":" << util::exactText(hi) << "]\n"
            << "set label "
            << quoted("range clipped: start-up peak q'" + n + " = " + shortText(range.peak) +
                      " rad/s at t = " + shortText(range.peak_time) + " s")
            << " at graph 0.01, graph 0.92 left boxed front\n";
      }
      o << "set xlabel \"time t [s]\"\nset ylabel " << quoted("q'" + n + named(j) + " [rad/s]") << "\nplot "
        << series(transport::kPlantTruth, column(truth_, indexed("qdot", j)), "q'" + n + " (PLANT_TRUTH)",
                  "lw 2");
      if (const std::string c = column(tracking_, indexed("qdot_desired", j)); !c.empty())
        o << ", " << series(kTrackingChannel, c, "q_d'" + n + " (reference)", "lw 1.5 dt 2");
      if (limited) {
        const double limit = spec_.velocity_limits[j];
        o << ", " << limit << " with lines dt 3 lw 1.5 lc rgb \"#d62728\" title "
          << quoted("velocity limit ±" + shortText(limit) + " rad/s (URDF)") << ", " << -limit
          << " with lines dt 3 lw 1.5 lc rgb \"#d62728\" notitle";
      }
      o << "\n";
    }
    end();
  }

  void torques() {
    std::vector<std::string> columns, titles;
    for (int j = 0; j < spec_.dof; ++j) {
      columns.push_back(indexed("tau_applied", j));
      titles.push_back("τ" + std::to_string(j + 1) + named(j));
    }
    if (!truth_.empty())
      signalPlot("torques.png", "torques applied by the plant", transport::kPlantTruth, truth_, columns,
                 titles, "τ", "N m");
    if (spec_.chain_order > 0 && !command_.empty()) {
      columns.clear();
      titles.clear();
      for (int j = 0; j < spec_.dof; ++j) {
        columns.push_back(indexed("u", j));
        titles.push_back("u" + std::to_string(j + 1) + named(j));
      }
      signalPlot("control_input.png", "controller output u (input of the actuator chain)",
                 transport::kControlCommand, command_, columns, titles, "u",
                 "N m / s^" + std::to_string(spec_.chain_order));
    }
  }

  // One line per column against time. When the start-up transient would
  // flatten the rest (signal_range.hpp), two panels: the start-up at full
  // range, then the whole run clipped to the range after it, saying so.
  void signalPlot(const std::string& png, const std::string& what, const char* channel,
                  const std::map<std::string, int>& cols, const std::vector<std::string>& columns,
                  const std::vector<std::string>& titles, const std::string& symbol,
                  const std::string& unit) {
    std::string lines;
    for (size_t j = 0; j < columns.size(); ++j)
      lines += (j ? ", " : "") + series(channel, column(cols, columns[j]), titles[j]);
    const std::string ylabel = "set ylabel " + quoted(symbol + " [" + unit + "]") + "\n";
    const SignalRange range = signalRange(
        (std::filesystem::path(spec_.dir) / (std::string(channel) + ".csv")).string(), columns, late_from_);
    if (!dominatedByStart(range) || late_from_ <= 0) {
      auto& o = begin(png, what);
      o << "set xlabel \"time t [s]\"\n" << ylabel << "plot " << lines << "\n";
      end();
      return;
    }
    const auto [lo, hi] = lateWindow(range);
    const std::string cut = shortText(late_from_);
    auto& o = begin(png, what, 2);
    o << "set xlabel \"time t [s]\"\n"
      << ylabel << "set title "
      << quoted("start-up, t ≤ " + cut + " s, full range: peak " + symbol + " = " + shortText(range.peak) +
                " " + unit + " (" + range.peak_column + ") at t = " + shortText(range.peak_time) + " s")
      << "\nset xrange [0:" << late_from_ << "]\nplot " << lines << "\n"
      << "set title "
      << quoted("whole run, range clipped to the values after t = " + cut + " s, [" + shortText(lo) + ", " +
                shortText(hi) + "] " + unit + ": the start-up peaks above are cut")
      << "\nset xrange [*:*]\nset yrange [" << util::exactText(lo) << ":" << util::exactText(hi) << "]\nplot "
      << lines << "\n";
    end();
  }

  void filterStates() {
    if (command_.empty()) return;
    auto& o = begin("filter_states.png", "dirty-derivative filter: output θ and state q_c", spec_.dof);
    for (int j = 0; j < spec_.dof; ++j) {
      const std::string n = std::to_string(j + 1);
      o << "set xlabel \"time t [s]\"\nset ylabel " << quoted("joint " + n + named(j) + " [rad/s]")
        << "\nplot "
        << series(transport::kControlCommand, column(command_, indexed("theta", j)),
                  "θ" + n + " = q_c + b q~", "lw 2")
        << ", "
        << series(transport::kControlCommand, column(command_, indexed("filter_state", j)), "q_c" + n,
                  "lw 1.5 dt 2")
        << "\n";
    }
    end();
  }

  void actuatorStates() {
    if (spec_.chain_order == 0 || actuator_.empty()) return;
    auto& o = begin("actuator_states.png", "actuator chain states ξ_i", spec_.chain_order);
    for (int i = 0; i < spec_.chain_order; ++i) {
      o << "set xlabel \"time t [s]\"\nset ylabel "
        << quoted("ξ" + std::to_string(i + 1) + " [N m / s^" + std::to_string(i) + "]") << "\nplot ";
      for (int j = 0; j < spec_.dof; ++j)
        o << (j ? ", " : "")
          << series(transport::kActuatorState, column(actuator_, indexed(indexed("xi", i), j)),
                    "joint " + std::to_string(j + 1) + named(j));
      o << "\n";
    }
    end();
  }

  void motors() {
    if (!spec_.flexible || motor_.empty()) return;
    auto& o = begin("motors.png", "motor angles q2 and link angles q1 (elastic joints)", spec_.dof);
    for (int j = 0; j < spec_.dof; ++j) {
      const std::string n = std::to_string(j + 1);
      o << "set xlabel \"time t [s]\"\nset ylabel " << quoted("joint " + n + named(j) + " [rad]") << "\nplot "
        << series(transport::kPlantMotor, column(motor_, indexed("q", j)), "motor q2_" + n, "lw 2");
      if (const std::string c = column(truth_, indexed("q", j)); !c.empty())
        o << ", " << series(transport::kPlantTruth, c, "link q1_" + n, "lw 1.5 dt 2");
      o << "\n";
    }
    end();
  }

  void timing() {
    if (timing_.empty()) return;
    auto& o = begin("timing.png", "realtime timing", 2);
    // Histograms: bins of 1/50 of the range, counts on a log scale so the tail shows.
    const int period = timing_.at("period_error_us"), command = timing_.at("command_latency_us"),
              actuator = timing_.at("actuator_latency_us");
    const std::string file = quoted(std::string(kTimingChannel) + ".csv");
    o << "set style fill solid 0.5\nset logscale y\nset ylabel \"count\"\nset yrange [0.8:*]\n";
    o << "stats " << file << " skip 1 using " << period << " nooutput\n"
      << "bw = (STATS_max > STATS_min) ? (STATS_max - STATS_min) / 50.0 : 1.0\n"
      << "set boxwidth bw absolute\n"
      << "set xlabel \"plant period error: actual − nominal [us]\"\n"
      << "plot " << file << " skip 1 using (bw * floor(column(" << period
      << ") / bw) + bw / 2):(1.0) smooth frequency with boxes lc rgb \"#1f77b4\" title sprintf(\"period "
         "error: median %.0f us, max %.0f us\", STATS_median, STATS_max)\n";
    o << "stats " << file << " skip 1 using " << actuator << " nooutput\n"
      << "med_a = STATS_median\nmax_a = STATS_max\nmin_a = STATS_min\n"
      << "stats " << file << " skip 1 using " << command << " nooutput\n"
      << "lo = (STATS_min < min_a) ? STATS_min : min_a\nhi = (STATS_max > max_a) ? STATS_max : max_a\n"
      << "bw = (hi > lo) ? (hi - lo) / 60.0 : 1.0\nset boxwidth bw absolute\n"
      << "set xlabel \"latency from the plant's sample [us]\"\n"
      << "plot " << file << " skip 1 using (bw * floor(column(" << command
      << ") / bw) + bw / 2):(1.0) smooth frequency with boxes lc rgb \"#ff7f0e\" title sprintf(\"to "
         "CONTROL_COMMAND: median %.0f us\", STATS_median), "
      << file << " skip 1 using (bw * floor(column(" << actuator
      << ") / bw) + bw / 2):(1.0) smooth frequency with boxes lc rgb \"#2ca02c\" title sprintf(\"to "
         "ACTUATOR_STATE: median %.0f us, max %.0f us\", med_a, max_a)\n";
    end();
  }

  const PlotSpec& spec_;
  std::map<std::string, int> truth_, command_, actuator_, motor_, timing_, tracking_;
  double late_from_ = 0.0;
  std::vector<Section> sections_;
  std::ostringstream out_;
};

// The time of the last row of DIR/CHANNEL.csv (0 when it has none).
double lastTime(const std::string& dir, const std::string& channel) {
  CsvRows rows((std::filesystem::path(dir) / (channel + ".csv")).string());
  const int time = rows.column("sim_time");
  double last = 0.0;
  std::vector<double> row;
  while (time >= 0 && rows.next(row))
    if (std::isfinite(row[time])) last = row[time];
  return last;
}

}  // namespace

std::string gnuplotString(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'')
      out += "''";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      out += ' ';
    else
      out += c;
  }
  return out + "'";
}

PlotSpec specFromCsv(const std::string& dir, const std::string& title) {
  PlotSpec spec;
  spec.dir = dir;
  spec.title = title;
  auto cols = columnsOf(dir, transport::kPlantTruth);
  if (cols.empty()) cols = columnsOf(dir, transport::kPlantPosition);
  while (cols.count(indexed("q", spec.dof))) ++spec.dof;
  const auto command = columnsOf(dir, transport::kControlCommand);
  if (spec.dof == 0)
    while (command.count(indexed("q_error", spec.dof))) ++spec.dof;
  while (command.count(indexed(indexed("xi_error", spec.chain_order), 0))) ++spec.chain_order;
  spec.flexible = !columnsOf(dir, transport::kPlantMotor).empty();
  spec.end_time = lastTime(dir, transport::kPlantTruth);
  if (spec.end_time == 0.0) spec.end_time = lastTime(dir, transport::kControlCommand);
  return spec;
}

PlotScript plotScript(const PlotSpec& spec) {
  PlotScript script;
  script.text =
      std::string("# gnuplot script written by lagrange report; run: cd THIS_DIR && gnuplot plots.gp\n") +
      kGnuplotPreamble;
  for (const Section& s : ScriptBuilder(spec).build()) {
    script.text += "\n" + s.text;
    script.pngs.push_back(s.png);
    script.sections.push_back(kGnuplotPreamble + s.text);
  }
  return script;
}

}  // namespace lagrange::tools
