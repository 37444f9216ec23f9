#include "tools/report/plots.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "tools/report/csv_export.hpp"
#include "transport/channels.hpp"
#include "util/output_stream.hpp"

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

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

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
  }

  std::vector<Section> build() {
    trackingError();
    chainError();
    joints();
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

  void trackingError() {
    const std::string norm = normOf(command_, "q_error", spec_.dof);
    if (norm.empty()) return;
    auto& o = begin("tracking_error.png", "tracking error norm (log scale)");
    o << "set logscale y\nset format y \"1e%T\"\nset xlabel \"time t [s]\"\n"
         "set ylabel \"‖q~‖ = ‖q − q_d‖ [rad]\"\n";
    o << "plot "
      << series(transport::kControlCommand, norm, "‖q~‖ (CONTROL_COMMAND.q_error)",
                "lw 2 lc rgb \"#1f77b4\"");
    if (spec_.tolerance > 0)
      o << ", " << spec_.tolerance << " with lines dt 2 lw 1.5 lc rgb \"gray30\" title "
        << quoted("metrics.tolerance = " + std::to_string(spec_.tolerance) + " rad");
    o << "\n";
    end();
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

  void torques() {
    if (!truth_.empty()) {
      auto& o = begin("torques.png", "torques applied by the plant");
      o << "set xlabel \"time t [s]\"\nset ylabel \"τ [N m]\"\nplot ";
      for (int j = 0; j < spec_.dof; ++j)
        o << (j ? ", " : "")
          << series(transport::kPlantTruth, column(truth_, indexed("tau_applied", j)),
                    "τ" + std::to_string(j + 1) + named(j));
      o << "\n";
      end();
    }
    if (spec_.chain_order > 0 && !command_.empty()) {
      auto& o = begin("control_input.png", "controller output u (input of the actuator chain)");
      o << "set xlabel \"time t [s]\"\nset ylabel "
        << quoted("u [N m / s^" + std::to_string(spec_.chain_order) + "]") << "\nplot ";
      for (int j = 0; j < spec_.dof; ++j)
        o << (j ? ", " : "")
          << series(transport::kControlCommand, column(command_, indexed("u", j)),
                    "u" + std::to_string(j + 1) + named(j));
      o << "\n";
      end();
    }
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
  std::map<std::string, int> truth_, command_, actuator_, motor_, timing_;
  std::vector<Section> sections_;
  std::ostringstream out_;
};

const char* kPreamble = kGnuplotPreamble;

// Runs gnuplot in `dir` with `script` on its standard input; its messages are
// appended to `log`. Returns gnuplot's exit status (127: not installed).
int runGnuplot(const std::string& dir, const std::string& script, const std::string& log) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw PlotError(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = fork();
  if (pid < 0) throw PlotError(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    dup2(pipe_fds[0], STDIN_FILENO);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    const int log_fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (log_fd >= 0) dup2(log_fd, STDERR_FILENO), dup2(log_fd, STDOUT_FILENO);
    if (chdir(dir.c_str()) != 0) _exit(126);
    execlp("gnuplot", "gnuplot", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipe_fds[0]);
  std::signal(SIGPIPE, SIG_IGN);
  const char* data = script.data();
  size_t left = script.size();
  while (left > 0) {
    const ssize_t n = write(pipe_fds[1], data, left);
    if (n <= 0) break;
    data += n;
    left -= static_cast<size_t>(n);
  }
  close(pipe_fds[1]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

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
  return spec;
}

PlotScript plotScript(const PlotSpec& spec) {
  PlotScript script;
  script.text =
      std::string("# gnuplot script written by lagrange report; run: cd THIS_DIR && gnuplot plots.gp\n") +
      kPreamble;
  for (const Section& s : ScriptBuilder(spec).build()) {
    script.text += "\n" + s.text;
    script.pngs.push_back(s.png);
    script.sections.push_back(kPreamble + s.text);
  }
  return script;
}

Plots drawPlots(const PlotSpec& spec) {
  const PlotScript script = plotScript(spec);
  {
    util::OutputStream out(fs::path(spec.dir) / "plots.gp");
    out << script.text;
    if (!out) throw PlotError("cannot write " + spec.dir + "/plots.gp");
  }
  return drawPictures(spec.dir, script.pngs, script.sections);
}

Plots drawPictures(const std::string& dir, const std::vector<std::string>& pngs,
                   const std::vector<std::string>& sections) {
  Plots plots;
  plots.log = (fs::path(dir) / "gnuplot.log").string();
  fs::remove(plots.log);
  // One gnuplot per picture, so a plot gnuplot rejects costs only itself.
  for (size_t i = 0; i < pngs.size(); ++i) {
    const fs::path png = fs::path(dir) / pngs[i];
    fs::remove(png);
    const int status = runGnuplot(dir, sections[i], plots.log);
    if (status == 127)
      throw PlotError(
          "gnuplot not found; install Debian's gnuplot-nox (bash scripts/setup.sh does) to get the "
          "plots; the CSV files are written");
    if (status == 0 && fs::exists(png) && fs::file_size(png) > 0)
      plots.written.push_back(png.string());
    else
      plots.failed.push_back(pngs[i]);
  }
  return plots;
}

}  // namespace lagrange::tools
