#include "tools/sweep/sweep_maps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <vector>

#include "util/output_stream.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;
using Row = nlohmann::ordered_json;

std::optional<double> numberOf(const Row& row, const std::string& column) {
  if (!row.contains(column)) return std::nullopt;
  const Row& v = row.at(column);
  if (v.is_number()) return v.get<double>();
  return std::nullopt;
}

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

// A parameter's value in a legend: 20, not 20.0.
std::string label(const Row& v) {
  if (!v.is_number()) return v.is_string() ? v.get<std::string>() : v.dump();
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v.get<double>());
  return buf;
}

std::string header(const std::string& png, const std::string& title) {
  return std::string(kGnuplotPreamble) + "set terminal pngcairo size 1000,650\nset output " +
         gnuplotString(png) + "\nset title " + gnuplotString(title) + " noenhanced\n";
}

// Values spread over a decade or more, all positive: a log axis.
bool wantsLog(const std::vector<double>& v) {
  if (v.empty()) return false;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *lo > 0 && *hi / *lo >= 10;
}

struct Picture {
  std::string png, script;
};

// What a swept column means on an axis: an initial-state norm axis is the
// size of that part of x(0); any other is the key it sets.
std::string axisTitle(const std::string& column) {
  if (column == "x0_norm") return "||x(0)|| = ||(q~(0), dq~(0), qc(0))||";
  if (column.size() > 5 && column.compare(column.size() - 5, 5, ".norm") == 0)
    return column + " (the norm of " + column.substr(0, column.size() - 5) + " - its reference value)";
  return column;
}

std::optional<Picture> convergenceMap(const fs::path& dir, const std::string& title,
                                      const std::map<long, Row>& rows, const std::string& xcol,
                                      const std::string& group) {
  // Against the swept axis `xcol`, one set of points per value of `group`
  // (another axis, when it has few values), by the group's value in numeric order.
  std::map<std::pair<double, std::string>, std::vector<std::pair<double, double>>> converged;
  std::vector<std::pair<double, std::string>> others;
  std::vector<double> xs, times;
  for (const auto& [i, r] : rows) {
    const auto x = numberOf(r, xcol);
    const auto t = numberOf(r, "convergence_time");
    if (!x) continue;
    xs.push_back(*x);
    const bool grouped = !group.empty() && r.contains(group);
    const std::pair<double, std::string> g = {grouped ? numberOf(r, group).value_or(0.0) : 0.0,
                                              grouped ? label(r.at(group)) : ""};
    if (t) {  // 0 too: a run that started within the tolerance converged at once
      converged[g].push_back({*x, *t});
      times.push_back(*t);
    } else {
      others.push_back({*x, r.value("diverged", false) ? "diverged" : "not converged"});
    }
  }
  if (converged.empty() && others.empty()) return std::nullopt;
  // Times on a log axis when they span a decade; those that did not converge above them.
  const bool log_y = wantsLog(times);
  const double longest = times.empty() ? 0.0 : *std::max_element(times.begin(), times.end());
  const double top = longest > 0 ? longest * (log_y ? 3.0 : 1.25) : 10.0;
  std::string plot = "plot ";
  int k = 0;
  for (const auto& [g, points] : converged) {
    const std::string file = "convergence_" + std::to_string(k) + ".csv";
    util::OutputStream out(dir / file);
    out << "x,convergence_time\n";
    for (const auto& [x, t] : points) out << num(x) << "," << num(t) << "\n";
    plot += std::string(k ? ", \\\n     " : "") + "'" + file +
            "' skip 1 using 1:2 with points pt 7 ps 0.6 title " +
            gnuplotString(g.second.empty() ? "converged" : group + " = " + g.second) + " noenhanced";
    ++k;
  }
  for (const std::string kind : {"not converged", "diverged"}) {
    std::vector<double> at;
    for (const auto& [x, what] : others)
      if (what == kind) at.push_back(x);
    if (at.empty()) continue;
    const std::string file = kind == "diverged" ? "diverged.csv" : "not_converged.csv";
    util::OutputStream out(dir / file);
    out << "x,y\n";
    const double y = kind == "diverged" ? (log_y ? top * 1.5 : top * 1.1) : top;
    for (double x : at) out << num(x) << "," << num(y) << "\n";
    plot += std::string(k++ ? ", \\\n     " : "") + "'" + file + "' skip 1 using 1:2 with points pt " +
            (kind == "diverged" ? "2" : "6") + " ps 0.8 title '" + kind + " (drawn above)'";
  }
  const bool log_x = wantsLog(xs);
  return Picture{"convergence_time.png",
                 header("convergence_time.png", title + ": convergence time against " + xcol) +
                     (log_x ? "set logscale x\nset format x '10^{%L}'\n" : "") +
                     (log_y ? "set logscale y\nset format y '10^{%L}'\n" : "set yrange [0:*]\n") +
                     "set offsets graph 0.03, graph 0.03, 0, 0\n"
                     "set xlabel " +
                     gnuplotString(axisTitle(xcol)) +
                     " noenhanced\n"
                     "set ylabel 'convergence time [s]'\nset key outside right\n" +
                     plot + "\n"};
}

std::optional<Picture> heatMap(const fs::path& dir, const std::string& title, const std::map<long, Row>& rows,
                               const std::string& xcol, const std::string& ycol) {
  std::map<std::pair<double, double>, std::pair<int, int>> cells;  // converged, runs
  std::vector<double> xs, ys;
  for (const auto& [i, r] : rows) {
    const auto x = numberOf(r, xcol), y = numberOf(r, ycol);
    if (!x || !y) continue;
    auto& c = cells[{*x, *y}];
    c.first += r.value("converged", false);
    ++c.second;
    xs.push_back(*x);
    ys.push_back(*y);
  }
  if (cells.empty()) return std::nullopt;
  util::OutputStream out(dir / "heat_map.csv");
  out << xcol << "," << ycol << ",converged_fraction,runs\n";
  for (const auto& [xy, c] : cells)
    out << num(xy.first) << "," << num(xy.second) << "," << num(double(c.first) / c.second) << "," << c.second
        << "\n";
  std::string script = header("heat_map.png", title + ": fraction of runs that converged") + "set xlabel " +
                       gnuplotString(xcol) + " noenhanced\nset ylabel " + gnuplotString(ycol) +
                       " noenhanced\nset cbrange [0:1]\nset cblabel 'converged fraction'\n"
                       "set palette defined (0 '#b2182b', 0.5 '#fdae61', 1 '#2166ac')\nset key off\n";
  if (wantsLog(xs)) script += "set logscale x\n";
  if (wantsLog(ys)) script += "set logscale y\n";
  script +=
      "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n"
      "plot 'heat_map.csv' skip 1 using 1:2:3 with points pt 5 ps 3 palette\n";
  return Picture{"heat_map.png", script};
}

std::optional<Picture> marginMap(const fs::path& dir, const std::string& title,
                                 const std::map<long, Row>& rows) {
  std::map<double, std::pair<int, int>> by_margin;
  for (const auto& [i, r] : rows)
    if (const auto m = numberOf(r, "gain_margin")) {
      auto& c = by_margin[*m];
      c.first += r.value("converged", false);
      ++c.second;
    }
  if (by_margin.empty()) return std::nullopt;
  util::OutputStream out(dir / "margin.csv");
  out << "gain_margin,converged_fraction,runs\n";
  for (const auto& [m, c] : by_margin)
    out << num(m) << "," << num(double(c.first) / c.second) << "," << c.second << "\n";
  return Picture{
      "margin.png",
      header("margin.png", title + ": the continuous-time condition against what was observed") +
          "set xlabel 'smallest margin of the evaluated continuous-time conditions (> 0: all hold)'\n"
          "set ylabel 'fraction of runs that converged'\nset yrange [-0.05:1.05]\n"
          "set arrow from 0, graph 0 to 0, graph 1 nohead dt 2\nset key off\n"
          "plot 'margin.csv' skip 1 using 1:2 with points pt 7 ps 1.2\n"};
}

// Per rate, over `size` (the swept initial-state norm, or ||x(0)||): the
// largest below which every run converged, and the largest that converged.
std::optional<Picture> regionMap(const fs::path& dir, const std::string& title,
                                 const std::map<long, Row>& rows, const std::string& size) {
  const std::string rate = "plant.publish_rate";
  std::map<double, std::vector<std::pair<double, bool>>> by_rate;
  for (const auto& [i, r] : rows) {
    const auto f = numberOf(r, rate), x = numberOf(r, size);
    if (f && x) by_rate[*f].push_back({*x, r.value("converged", false)});
  }
  if (by_rate.size() < 2) return std::nullopt;
  util::OutputStream out(dir / "region_vs_rate.csv");
  out << "rate,all_converged_below,largest_converged,runs\n";
  // A rate where no run converged has no region: drawn as a cross below the
  // smallest initial state swept, so that it is not silently missing; one
  // where some run of the smallest size failed has no "every run below":
  // drawn as a triangle there.
  double smallest = 0;
  for (const auto& [f, runs] : by_rate)
    for (const auto& [x, ok] : runs) smallest = smallest > 0 ? std::min(smallest, x) : x;
  util::OutputStream none(dir / "region_none.csv"), partial(dir / "region_smallest_failed.csv");
  none << "rate,y\n";
  partial << "rate,y\n";
  bool any_none = false, any_partial = false;
  for (auto& [f, runs] : by_rate) {
    std::sort(runs.begin(), runs.end());
    double all_below = 0, largest = 0;
    bool intact = true;
    for (const auto& [x, ok] : runs) {
      intact = intact && ok;
      if (intact) all_below = x;
      if (ok) largest = x;
    }
    if (largest == 0) {
      none << num(f) << "," << num(smallest / 2) << "\n";
      any_none = true;
      continue;
    }
    if (all_below == 0) {
      partial << num(f) << "," << num(smallest / 2) << "\n";
      any_partial = true;
    }
    out << num(f) << "," << (all_below > 0 ? num(all_below) : "") << "," << num(largest) << "," << runs.size()
        << "\n";
  }
  std::string crosses = any_none ? ", \\\n     'region_none.csv' skip 1 using 1:2 with points pt 2 ps "
                                   "2 lw 2 title 'no run converged'"
                                 : "";
  if (any_partial)
    crosses +=
        ", \\\n     'region_smallest_failed.csv' skip 1 using 1:2 with points pt 11 ps 2 lw 2 title "
        "'a run of the smallest size did not converge'";
  return Picture{
      "region_vs_rate.png",
      header("region_vs_rate.png", title + ": region of convergence against the controller rate") +
          "set logscale xy\nset xlabel 'controller rate, plant.publish_rate [Hz]' noenhanced\n"
          "set ylabel " +
          gnuplotString(axisTitle(size)) +
          " noenhanced\nset key top left box opaque\n"
          "plot 'region_vs_rate.csv' skip 1 using 1:2 with linespoints lw 2 pt 7 title "
          "'every run from below converged', \\\n"
          "     '' skip 1 using 1:3 with linespoints lw 2 pt 6 dt 2 title 'largest that converged'" +
          crosses + "\n"};
}

}  // namespace

SweepMaps drawSweepMaps(const std::string& out_dir, const SweepPlan& plan, const std::map<long, Row>& rows) {
  const fs::path dir = fs::path(out_dir) / "maps";
  util::makeOutputDirectories(dir.string());
  const std::string title = fs::path(plan.spec.file).stem().string();
  SweepMaps maps;
  // Parameter columns a map can use: not a norm axis's direction index.
  std::vector<std::string> axes;
  for (const std::string& c : plan.param_columns)
    if (c.size() < 10 || c.compare(c.size() - 10, 10, ".direction") != 0) axes.push_back(c);
  std::map<std::string, size_t> distinct;  // numeric values per axis
  for (const std::string& a : axes) {
    std::set<double> values;
    for (const auto& [i, r] : rows)
      if (const auto v = numberOf(r, a)) values.insert(*v);
    distinct[a] = values.size();
  }
  // The convergence map's x: the axis swept over the most values (the first
  // of equals); its points grouped by the first other axis of 2 to 8 values.
  // A sweep of no numeric axis falls back on ||x(0)||.
  std::string xcol = "x0_norm", group;
  for (const std::string& a : axes)
    if (distinct[a] > 1 && (xcol == "x0_norm" || distinct[a] > distinct[xcol])) xcol = a;
  for (const std::string& a : axes)
    if (a != xcol && distinct[a] >= 2 && distinct[a] <= 8) {
      group = a;
      break;
    }
  std::vector<Picture> pictures;
  if (auto p = convergenceMap(dir, title, rows, xcol, group))
    pictures.push_back(*p);
  else
    maps.not_drawn.push_back("convergence_time.png: no finished run has a value of " + xcol);
  const std::vector<std::string> heat = plan.spec.heat_map.size() == 2 ? plan.spec.heat_map : axes;
  if (heat.size() < 2)
    maps.not_drawn.push_back("heat_map.png: the sweep has " + std::to_string(axes.size()) +
                             (axes.size() == 1 ? " axis" : " axes") +
                             "; a heat map needs two (maps.heat_map names them)");
  else if (auto p = heatMap(dir, title, rows, heat[0], heat[1]))
    pictures.push_back(*p);
  else
    maps.not_drawn.push_back("heat_map.png: no finished run has numbers in both " + heat[0] + " and " +
                             heat[1]);
  std::set<double> margins;
  for (const auto& [i, r] : rows)
    if (const auto m = numberOf(r, "gain_margin")) margins.insert(*m);
  if (margins.size() >= 2) {
    if (auto p = marginMap(dir, title, rows)) pictures.push_back(*p);
  } else {
    maps.not_drawn.push_back(
        margins.empty() ? "margin.png: no run has an evaluated gain condition (gain_margin)"
                        : "margin.png: every run has the same gain margin (" + num(*margins.begin()) +
                              "): the sweep does not vary what the condition depends on");
  }
  // The region's size: the first initial-state norm swept (over every other
  // axis and direction), else ||x(0)||.
  std::string size = "x0_norm";
  for (const std::string& a : axes)
    if (a.size() > 5 && a.compare(a.size() - 5, 5, ".norm") == 0 && distinct[a] > 1) {
      size = a;
      break;
    }
  if (auto p = regionMap(dir, title, rows, size))
    pictures.push_back(*p);
  else
    maps.not_drawn.push_back("region_vs_rate.png: plant.publish_rate is not swept over two values or more");
  std::vector<std::string> pngs, sections;
  std::string all;
  for (const std::string& why : maps.not_drawn) all += "# not drawn: " + why + "\n";
  for (const Picture& p : pictures) {
    pngs.push_back(p.png);
    sections.push_back(p.script);
    all += p.script + "\n";
  }
  util::writeOutputFile((dir / "maps.gp").string(), all);
  maps.plots = drawPictures(dir.string(), pngs, sections);
  return maps;
}

}  // namespace lagrange::tools
