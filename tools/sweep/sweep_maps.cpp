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
  return std::string(kGnuplotPreamble) + "set terminal pngcairo size 1000,650\nset output '" + png +
         "'\nset title '" + title + "' noenhanced\n";
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

std::optional<Picture> convergenceMap(const fs::path& dir, const std::string& title,
                                      const std::map<long, Row>& rows, const std::string& group) {
  // One curve per value of `group` (the first axis, when it has few values).
  // By the group's value, numbers in numeric order.
  std::map<std::pair<double, std::string>, std::vector<std::pair<double, double>>> converged;
  std::vector<std::pair<double, std::string>> others;
  double top = 0;
  for (const auto& [i, r] : rows) {
    const auto x = numberOf(r, "x0_norm");
    const auto t = numberOf(r, "convergence_time");
    if (!x || *x <= 0) continue;
    const bool grouped = !group.empty() && r.contains(group);
    const std::pair<double, std::string> g = {grouped ? numberOf(r, group).value_or(0.0) : 0.0,
                                              grouped ? label(r.at(group)) : ""};
    if (t && *t > 0) {
      converged[g].push_back({*x, *t});
      top = std::max(top, *t);
    } else {
      others.push_back({*x, r.value("diverged", false) ? "diverged" : "not converged"});
    }
  }
  if (converged.empty() && others.empty()) return std::nullopt;
  top = top > 0 ? top * 3 : 10;
  std::string plot = "plot ";
  int k = 0;
  for (const auto& [g, points] : converged) {
    const std::string file = "convergence_" + std::to_string(k) + ".csv";
    util::OutputStream out(dir / file);
    out << "x0_norm,convergence_time\n";
    for (const auto& [x, t] : points) out << num(x) << "," << num(t) << "\n";
    plot += std::string(k ? ", \\\n     " : "") + "'" + file +
            "' skip 1 using 1:2 with points pt 7 ps 0.6 title '" +
            (g.second.empty() ? "converged" : group + " = " + g.second) + "' noenhanced";
    ++k;
  }
  for (const std::string kind : {"not converged", "diverged"}) {
    std::vector<double> xs;
    for (const auto& [x, what] : others)
      if (what == kind) xs.push_back(x);
    if (xs.empty()) continue;
    const std::string file = kind == "diverged" ? "diverged.csv" : "not_converged.csv";
    util::OutputStream out(dir / file);
    out << "x0_norm,y\n";
    for (double x : xs) out << num(x) << "," << num(top * (kind == "diverged" ? 1.5 : 1.0)) << "\n";
    plot += std::string(k++ ? ", \\\n     " : "") + "'" + file + "' skip 1 using 1:2 with points pt " +
            (kind == "diverged" ? "2" : "6") + " ps 0.8 title '" + kind + " (drawn above)'";
  }
  return Picture{"convergence_time.png",
                 header("convergence_time.png", title + ": convergence time against the initial state") +
                     "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
                     "set xlabel '||x(0)|| = ||(q~(0), dq~(0), qc(0))||' noenhanced\n"
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
  std::string script = header("heat_map.png", title + ": fraction of runs that converged") + "set xlabel '" +
                       xcol + "' noenhanced\nset ylabel '" + ycol +
                       "' noenhanced\nset cbrange [0:1]\nset cblabel 'converged fraction'\n"
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

std::optional<Picture> regionMap(const fs::path& dir, const std::string& title,
                                 const std::map<long, Row>& rows) {
  const std::string rate = "plant.publish_rate";
  std::map<double, std::vector<std::pair<double, bool>>> by_rate;
  for (const auto& [i, r] : rows) {
    const auto f = numberOf(r, rate), x = numberOf(r, "x0_norm");
    if (f && x) by_rate[*f].push_back({*x, r.value("converged", false)});
  }
  if (by_rate.size() < 2) return std::nullopt;
  util::OutputStream out(dir / "region_vs_rate.csv");
  out << "rate,all_converged_below,largest_converged,runs\n";
  // A rate where no run converged has no region: drawn as a cross below the
  // smallest initial state swept, so that it is not silently missing.
  double smallest = 0;
  for (const auto& [f, runs] : by_rate)
    for (const auto& [x, ok] : runs) smallest = smallest > 0 ? std::min(smallest, x) : x;
  util::OutputStream none(dir / "region_none.csv");
  none << "rate,y\n";
  bool any_none = false;
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
    out << num(f) << "," << num(all_below) << "," << num(largest) << "," << runs.size() << "\n";
  }
  const std::string crosses = any_none ? ", \\\n     'region_none.csv' skip 1 using 1:2 with points pt 2 ps "
                                         "2 lw 2 title 'no run converged'"
                                       : "";
  return Picture{
      "region_vs_rate.png",
      header("region_vs_rate.png", title + ": region of convergence against the controller rate") +
          "set logscale xy\nset xlabel 'controller rate, plant.publish_rate [Hz]' noenhanced\n"
          "set ylabel '||x(0)||'\nset key top left box opaque\n"
          "plot 'region_vs_rate.csv' skip 1 using 1:2 with linespoints lw 2 pt 7 title "
          "'every run from below converged', \\\n"
          "     '' skip 1 using 1:3 with linespoints lw 2 pt 6 dt 2 title 'largest that converged'" +
          crosses + "\n"};
}

}  // namespace

Plots drawSweepMaps(const std::string& out_dir, const SweepPlan& plan, const std::map<long, Row>& rows) {
  const fs::path dir = fs::path(out_dir) / "maps";
  util::makeOutputDirectories(dir.string());
  const std::string title = fs::path(plan.spec.file).stem().string();
  // Parameter columns a map can use: not a norm axis's direction index.
  std::vector<std::string> axes;
  for (const std::string& c : plan.param_columns)
    if (c.size() < 10 || c.compare(c.size() - 10, 10, ".direction") != 0) axes.push_back(c);
  std::string group;
  if (!axes.empty() && axes[0].find(".norm") == std::string::npos) {
    std::set<std::string> values;
    for (const auto& [i, r] : rows)
      if (r.contains(axes[0])) values.insert(r.at(axes[0]).dump());
    if (values.size() <= 8) group = axes[0];
  }
  std::vector<Picture> pictures;
  if (auto p = convergenceMap(dir, title, rows, group)) pictures.push_back(*p);
  const std::vector<std::string> heat = plan.spec.heat_map.size() == 2 ? plan.spec.heat_map : axes;
  if (heat.size() >= 2)
    if (auto p = heatMap(dir, title, rows, heat[0], heat[1])) pictures.push_back(*p);
  if (auto p = marginMap(dir, title, rows)) pictures.push_back(*p);
  if (auto p = regionMap(dir, title, rows)) pictures.push_back(*p);
  std::vector<std::string> pngs, sections;
  std::string all;
  for (const Picture& p : pictures) {
    pngs.push_back(p.png);
    sections.push_back(p.script);
    all += p.script + "\n";
  }
  util::writeOutputFile((dir / "maps.gp").string(), all);
  return drawPictures(dir.string(), pngs, sections);
}

}  // namespace lagrange::tools
