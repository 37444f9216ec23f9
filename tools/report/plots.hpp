#pragma once
/// @file
/// `lagrange report`, its pictures: PNG plots of a run drawn by gnuplot from
/// the CSV files of csv_export.hpp. gnuplot (Debian's gnuplot-nox, cairo
/// PNG terminal) rather than matplotlib: one small C program with no Python
/// stack, it reads the CSV files as they are, and the generated script
/// (plots.gp, kept next to the PNGs) is a readable starting point for a
/// user's own figures.

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/error.hpp"

namespace lagrange::tools {

/// gnuplot missing or failing; the CSV files are written regardless.
class PlotError : public lagrange::RuntimeFault {
 public:
  using lagrange::RuntimeFault::RuntimeFault;
};

/// What the plots need to know about the run.
struct PlotSpec {
  std::string dir;         ///< holds CHANNEL.csv; the PNGs and plots.gp go here
  std::string title;       ///< names the scenario, e.g. "rigid_2dof (lockstep, theorem1)"
  int dof = 0;             ///< joints
  int chain_order = 0;     ///< actuator integrators m (stage plots when > 0)
  bool flexible = false;   ///< motor positions plotted against the links'
  double tolerance = 0.0;  ///< metrics.tolerance [rad], drawn on the error plot (0: none)
  /// The robot's joint names, base to tip (a URDF arm's), shown next to the
  /// joint numbers; empty, or the planar chain's "joint1".., for numbers alone.
  std::vector<std::string> joint_names;
  /// The run's convergence time (tracking_table.hpp, as summary.json's),
  /// marked on the error plots; when TRACKING.csv exists and this is empty,
  /// the plots say the run did not converge.
  std::optional<double> convergence_time;
  double end_time = 0.0;  ///< the last sample's time [s] (0: unknown)
  /// Per joint [rad/s], +inf where none: a URDF's <limit velocity>, drawn on
  /// the rate plots (empty: no limits).
  std::vector<double> velocity_limits;
};

/// What the CSV files in `dir` say about the run, for a log without a scenario.
PlotSpec specFromCsv(const std::string& dir, const std::string& title);

/// The gnuplot script for `spec` (only plots whose CSV files exist), and the PNG names it writes.
struct PlotScript {
  std::string text;                   ///< the whole script (plots.gp)
  std::vector<std::string> pngs;      ///< file names, one per picture
  std::vector<std::string> sections;  ///< a self-contained script per picture
};
PlotScript plotScript(const PlotSpec& spec);

struct Plots {
  std::vector<std::string> written;  ///< PNG paths
  std::vector<std::string> failed;   ///< PNG names gnuplot could not draw (its messages in `log`)
  std::string log;                   ///< DIR/gnuplot.log
};

/// Writes DIR/plots.gp and runs gnuplot once per picture.
/// @throws PlotError when gnuplot is not installed or plots.gp cannot be written.
Plots drawPlots(const PlotSpec& spec);

/// `text` as a gnuplot string: single-quoted, a quote doubled, control
/// characters (a newline would end the command) as spaces. Never double
/// quotes: gnuplot runs `backquoted` shell commands inside those, and a log's
/// scenario and joint names, a sweep's values, are not ours to trust.
std::string gnuplotString(const std::string& text);

/// The start of every picture's script: CSV input, a grid, a boxed key.
inline constexpr const char* kGnuplotPreamble =
    "set datafile separator \",\"\nset grid\nset key top right box opaque\n";

/// Runs gnuplot in `dir` once per picture: sections[i], a whole script, draws
/// pngs[i]; gnuplot's messages go to DIR/gnuplot.log.
/// @throws PlotError when gnuplot is not installed.
Plots drawPictures(const std::string& dir, const std::vector<std::string>& pngs,
                   const std::vector<std::string>& sections);

}  // namespace lagrange::tools
