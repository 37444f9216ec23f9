#pragma once
/// @file
/// `lagrange sweep`, its maps: PNGs drawn by gnuplot from the table, each
/// with the data file it plots (OUT/maps/*.csv) and its script (maps.gp):
///  - convergence_time.png: convergence time against ||x(0)|| (log axes),
///    runs that did not converge drawn apart above them;
///  - heat_map.png: the fraction of runs that converged over two parameter
///    columns (maps.heat_map; default the first two axes);
///  - margin.png: eq. (11)'s margin against the fraction that converged, per
///    gain setting (where the condition fails yet runs converge);
///  - region_vs_rate.png: with plant.publish_rate among the axes, per rate the
///    largest ||x(0)|| below which every run converged, and the largest that
///    converged. Maps whose columns the sweep lacks are not drawn.

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/report/plots.hpp"
#include "tools/sweep/sweep_plan.hpp"

namespace lagrange::tools {

/// @throws PlotError when gnuplot is missing (the table is written regardless).
Plots drawSweepMaps(const std::string& out_dir, const SweepPlan& plan,
                    const std::map<long, nlohmann::ordered_json>& rows);

}  // namespace lagrange::tools
