#pragma once
/// @file
/// `lagrange sweep`, its maps: PNGs drawn by gnuplot from the table, each
/// with the data file it plots (OUT/maps/*.csv) and its script (maps.gp):
///  - convergence_time.png: convergence time against the axis swept over the
///    most values (||x(0)|| when no axis is numeric), grouped by another axis
///    of 2 to 8 values; runs that did not converge drawn apart above them;
///  - heat_map.png: the fraction of runs that converged over two parameter
///    columns (maps.heat_map; default the first two axes);
///  - margin.png: eq. (11)'s margin against the fraction that converged, per
///    gain setting (where the condition fails yet runs converge), when the
///    margin takes two values or more;
///  - region_vs_rate.png: with plant.publish_rate among the axes, per rate the
///    largest ||x(0)|| below which every run converged, and the largest that
///    converged.
/// A map not drawn is named with the reason (`not_drawn`, and maps.gp).

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/report/plots.hpp"
#include "tools/sweep/sweep_plan.hpp"

namespace lagrange::tools {

struct SweepMaps {
  Plots plots;
  std::vector<std::string> not_drawn;  ///< "NAME.png: why", one per map left out
};

/// @throws PlotError when gnuplot is missing (the table is written regardless).
SweepMaps drawSweepMaps(const std::string& out_dir, const SweepPlan& plan,
                        const std::map<long, nlohmann::ordered_json>& rows);

}  // namespace lagrange::tools
