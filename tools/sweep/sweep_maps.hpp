#pragma once
/// @file
/// `lagrange sweep`, its maps: PNGs drawn by gnuplot from the table, each
/// with the data file it plots (OUT/maps/*.csv) and its script (maps.gp).
/// Every map reads each row's verdict (the `verdict` and `verdict_kind`
/// columns: logger/verdict.hpp, as `lagrange run` decides it) and never
/// decides again whether a run met its metric:
///  - convergence_time.png: convergence time against the axis swept over the
///    most values (numbers on a numeric axis, the values in order otherwise),
///    a mark per verdict class -- met, NOT met with its likeliest reason
///    (diverged, unstable at rate, timing, saturated, ...), not judged --
///    coloured by another axis of 2 to 8 values; runs without a convergence
///    time drawn above the others; a sweep of one axis joins the median
///    convergence time at each value with a line;
///  - heat_map.png: the fraction of runs whose verdict is met over two
///    parameter columns: maps.heat_map's, drawn as asked (a note when one
///    holds one value); by default the first two axes that vary -- an axis
///    of one value is never chosen, and with one varying axis there is no
///    heat map (convergence_time.png draws against it). Numbers at their
///    values; vectors, maps and texts each a tick named by its value;
///  - margin.png: eq. (11)'s margin against the fraction met, per gain
///    setting (where the condition fails yet runs meet the metric), when the
///    margin takes two values or more;
///  - region_vs_rate.png: with plant.publish_rate among the axes, per rate the
///    largest initial-state size below which every run met the metric, and
///    the largest that met it.
/// A map not drawn is named with the reason (`not_drawn`, and maps.gp).

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/report/plots.hpp"
#include "tools/sweep/sweep_plan.hpp"

namespace lagrange::tools {

/// How the maps draw a row: its verdict as the row says it.
struct VerdictClass {
  std::string key;    ///< a file-name word: met, not_met_diverged, not_met, not_judged, failed, no_verdict
  std::string label;  ///< the legend's: "met", "NOT met: diverged", "not judged", ...
  bool met = false;   ///< the verdict is `met`
};

/// A row's class, from its `verdict` (met | NOT met | not judged) and, when
/// not met, its `verdict_kind` (the likeliest reason's kind: "NOT met:
/// unstable at rate"); a row without a verdict is `failed` (status failed:
/// the run could not be made) or `no verdict` (a row of a sweep from before
/// verdicts). Never from `converged`, `diverged` or the errors.
VerdictClass verdictClass(const nlohmann::ordered_json& row);

/// The maps' data files and scripts, written into OUT/maps/ without running gnuplot.
struct SweepMapFiles {
  std::vector<std::string> pngs;           ///< the pictures to draw
  std::vector<std::string> scripts;        ///< a whole gnuplot script per picture
  std::vector<std::string> not_drawn;      ///< "NAME.png: why", one per map left out
  std::vector<std::string> notes;          ///< "NAME.png: what to know", of a map drawn
  std::string convergence_axis;            ///< the column convergence_time.png is drawn against
  std::vector<std::string> heat_map_axes;  ///< heat_map.png's x and y columns; empty when not drawn
  /// convergence_time.png's legend classes (VerdictClass::label), in drawing order.
  std::vector<std::string> convergence_classes;
};
SweepMapFiles writeSweepMapFiles(const std::string& out_dir, const SweepPlan& plan,
                                 const std::map<long, nlohmann::ordered_json>& rows);

struct SweepMaps {
  Plots plots;
  std::vector<std::string> not_drawn;  ///< "NAME.png: why", one per map left out
  std::vector<std::string> notes;      ///< "NAME.png: what to know", of a map drawn
};

/// writeSweepMapFiles, maps.gp, then gnuplot once per picture.
/// @throws PlotError when gnuplot is missing (the table is written regardless).
SweepMaps drawSweepMaps(const std::string& out_dir, const SweepPlan& plan,
                        const std::map<long, nlohmann::ordered_json>& rows);

}  // namespace lagrange::tools
