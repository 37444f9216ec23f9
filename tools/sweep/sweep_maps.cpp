#include "tools/sweep/sweep_maps.hpp"

#include <algorithm>
#include <cctype>
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

std::string textOf(const Row& row, const std::string& column) {
  const auto v = row.find(column);
  return v != row.end() && v->is_string() ? v->get<std::string>() : "";
}

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

// A parameter's value in a legend or on an axis: 20, not 20.0; a vector
// gain [20, 30] and a map {mass: 2, com: 0.1} as their YAML was written,
// not [20.0,30.0].
std::string label(const Row& v) {
  if (v.is_array()) {
    std::string text = "[";
    for (size_t i = 0; i < v.size(); ++i) text += (i ? ", " : "") + label(v[i]);
    return text + "]";
  }
  if (v.is_object()) {  // a map value ({mass: 2, com: 0.1}), in the order written
    std::string text = "{";
    for (auto it = v.begin(); it != v.end(); ++it)
      text += (it == v.begin() ? "" : ", ") + it.key() + ": " + label(it.value());
    return text + "}";
  }
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

// How each class is marked: a gnuplot point type and size, and its colour
// when the points are not coloured by another axis.
struct Mark {
  int type;
  double size;
  const char* colour;
};
Mark markOf(const std::string& key) {
  if (key == "met") return {7, 0.7, "#2166ac"};
  if (key == "not_met_diverged") return {2, 1.0, "#b2182b"};
  if (key == "not_met_unstable_at_rate") return {3, 1.0, "#d6604d"};
  if (key == "not_met_timing" || key == "not_met_stale_torque") return {8, 1.0, "#8c510a"};
  if (key == "not_met_saturated") return {5, 0.8, "#e08214"};
  if (key == "not_met_late") return {4, 0.9, "#7b3294"};
  if (key == "not_met_not_converged") return {6, 0.9, "#c51b7d"};
  if (key == "not_met_condition_violated") return {12, 1.0, "#4d9221"};
  if (key.rfind("not_met", 0) == 0) return {10, 1.0, "#b35806"};
  if (key == "not_judged") return {1, 1.0, "#777777"};
  return {11, 1.0, "#000000"};  // failed, no verdict
}

// The drawing (and legend) order of the classes: met, NOT met by reason, then the rest.
int classRank(const std::string& key) {
  if (key == "met") return 0;
  if (key.rfind("not_met", 0) == 0) return 1;
  if (key == "not_judged") return 2;
  return 3;
}

// An axis's values over the rows: numbers, or texts drawn in order of appearance.
struct AxisValues {
  bool numeric = true;
  std::set<double> numbers;
  std::vector<std::string> texts;  // distinct, in the order of the rows
  size_t distinct() const { return numeric ? numbers.size() : texts.size(); }
};
AxisValues valuesOf(const std::map<long, Row>& rows, const std::string& column) {
  AxisValues a;
  std::set<std::string> seen;
  for (const auto& [i, r] : rows) {
    const auto v = r.find(column);
    if (v == r.end() || v->is_null()) continue;
    if (v->is_number())
      a.numbers.insert(v->get<double>());
    else
      a.numeric = false;
    if (const std::string t = label(*v); seen.insert(t).second) a.texts.push_back(t);
  }
  return a;
}

// An axis of values that are not numbers: each value a tick at its place
// (0, 1, ... in the order the rows first hold it), named by the value.
std::string namedTics(const char* axis, const std::vector<std::string>& texts) {
  std::string tics;
  for (size_t k = 0; k < texts.size(); ++k)
    tics += (k ? ", " : "") + gnuplotString(texts[k].substr(0, 24)) + " " + std::to_string(k);
  const bool rotate = axis[0] == 'x' && texts.size() > 6;  // long names side by side overlap
  return std::string("set ") + axis + "range [-0.5:" + num(static_cast<double>(texts.size()) - 0.5) +
         "]\nset " + axis + "tics (" + tics + ") noenhanced" + (rotate ? " rotate by -30" : "") + "\n";
}

// A row's place on an axis: its number on a numeric axis, its value's place
// on another; none when the row has no value there.
std::optional<double> placeOf(const Row& row, const std::string& column, const AxisValues& axis) {
  const auto v = row.find(column);
  if (v == row.end() || v->is_null()) return std::nullopt;
  if (axis.numeric) return v->is_number() ? std::optional<double>(v->get<double>()) : std::nullopt;
  const auto at = std::find(axis.texts.begin(), axis.texts.end(), label(*v));
  if (at == axis.texts.end()) return std::nullopt;
  return static_cast<double>(at - axis.texts.begin());
}

// A CSV field: quoted, so that a vector's commas stay in it.
std::string csvQuoted(const std::string& text) {
  std::string q = "\"";
  for (const char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// "controller.a has one value (50)"; the column of an axis that varies not at all.
std::string oneValue(const std::string& column, const AxisValues& axis) {
  if (axis.distinct() == 0) return column + " has no value in any run";
  return column + " has one value (" + axis.texts.front() + ")";
}

struct ConvergenceMap {
  Picture picture;
  std::vector<std::string> classes;
};

std::optional<ConvergenceMap> convergenceMap(const fs::path& dir, const std::string& title,
                                             const std::map<long, Row>& rows, const std::string& xcol,
                                             const AxisValues& xvalues, const std::string& group, bool line) {
  // A point per row: x on the swept axis (a number, or the place of its
  // value), y its convergence time or none, its group and its class.
  struct Point {
    double x;
    std::optional<double> t;
    int group;
  };
  std::map<std::pair<int, std::string>, std::pair<VerdictClass, std::vector<Point>>> by_class;
  std::vector<std::string> groups;  // a group's values, in numeric order when numbers
  if (!group.empty()) {
    const AxisValues g = valuesOf(rows, group);
    if (g.numeric)
      for (double v : g.numbers) groups.push_back(label(Row(v)));
    else
      groups = g.texts;
  }
  std::vector<double> xs, times;
  for (const auto& [i, r] : rows) {
    const auto v = r.find(xcol);
    if (v == r.end() || v->is_null()) continue;
    double x = 0;
    if (xvalues.numeric) {
      if (!v->is_number()) continue;
      x = v->get<double>();
    } else {
      x = static_cast<double>(std::find(xvalues.texts.begin(), xvalues.texts.end(), label(*v)) -
                              xvalues.texts.begin());
    }
    int g = 0;
    if (!groups.empty() && r.contains(group))
      g = static_cast<int>(std::find(groups.begin(), groups.end(), label(r.at(group))) - groups.begin());
    const VerdictClass c = verdictClass(r);
    auto& entry = by_class[{classRank(c.key), c.key}];
    entry.first = c;
    const auto t = numberOf(r, "convergence_time");  // 0 too: a run that started within the tolerance
    entry.second.push_back({x, t, g});
    xs.push_back(x);
    if (t) times.push_back(*t);
  }
  if (by_class.empty()) return std::nullopt;
  // Times on a log axis when they span a decade; runs without one above them.
  const bool log_y = wantsLog(times);
  const double longest = times.empty() ? 0.0 : *std::max_element(times.begin(), times.end());
  const double top = longest > 0 ? longest * (log_y ? 3.0 : 1.25) : 1.0;
  bool above = false;
  ConvergenceMap map;
  std::string plot;
  const auto add = [&plot](const std::string& item) {
    plot += (plot.empty() ? "plot " : ", \\\n     ") + item;
  };
  for (const auto& [rank_key, entry] : by_class) {
    const auto& [c, points] = entry;
    const std::string file = "convergence_" + c.key + ".csv";
    util::OutputStream out(dir / file);
    out << "x,y,group\n";
    for (const Point& p : points) {
      above = above || !p.t;
      out << num(p.x) << "," << num(p.t ? *p.t : top) << "," << p.group + 1 << "\n";
    }
    const Mark m = markOf(c.key);
    const std::string style = "with points pt " + std::to_string(m.type) + " ps " + num(m.size);
    if (groups.empty()) {
      add("'" + file + "' skip 1 using 1:2 " + style + " lc rgb '" + m.colour + "' title " +
          gnuplotString(c.label) + " noenhanced");
    } else {  // colours say the group; the class is the mark, shown in black in the key
      add("'" + file + "' skip 1 using 1:2:3 " + style + " lc variable notitle");
      add("NaN " + style + " lc rgb 'black' title " + gnuplotString(c.label) + " noenhanced");
    }
    map.classes.push_back(c.label);
  }
  for (size_t g = 0; g < groups.size(); ++g)
    add("NaN with points pt 7 ps 1 lc " + std::to_string(g + 1) + " title " +
        gnuplotString(group + " = " + groups[g]) + " noenhanced");
  if (line && !times.empty()) {  // one axis: the median time at each of its values, joined
    std::map<double, std::vector<double>> at;
    for (const auto& [rank_key, entry] : by_class)
      for (const Point& p : entry.second)
        if (p.t) at[p.x].push_back(*p.t);
    util::OutputStream out(dir / "convergence_median.csv");
    out << "x,median_convergence_time\n";
    for (auto& [x, ts] : at) {
      std::sort(ts.begin(), ts.end());
      const size_t n = ts.size();
      out << num(x) << "," << num(n % 2 ? ts[n / 2] : (ts[n / 2 - 1] + ts[n / 2]) / 2) << "\n";
    }
    plot =
        "plot 'convergence_median.csv' skip 1 using 1:2 with lines lw 1.5 lc rgb '#555555' title "
        "'median convergence time at each value', \\\n     " +
        plot.substr(5);
  }
  std::string script =
      header("convergence_time.png", title + ": convergence time, each run marked by its verdict");
  if (xvalues.numeric) {
    if (wantsLog(xs)) script += "set logscale x\nset format x '10^{%L}'\n";
    script += "set offsets graph 0.03, graph 0.03, 0, 0\n";
  } else {  // the values in order, each named
    script += namedTics("x", xvalues.texts);
  }
  if (log_y)
    script += "set logscale y\nset format y '10^{%L}'\n";
  else
    script += "set yrange [0:*]\n";
  if (above && !times.empty()) {  // the band of runs without a convergence time
    const double line_at = log_y ? std::sqrt(longest * top) : (longest + top) / 2;
    script += "set arrow from graph 0, first " + num(line_at) + " to graph 1, first " + num(line_at) +
              " nohead dt 3 lc rgb '#999999'\n";
  }
  script +=
      "set xlabel " + gnuplotString(axisTitle(xcol)) + " noenhanced\nset ylabel " +
      gnuplotString(above ? "convergence time [s] (at the top: runs without one)" : "convergence time [s]") +
      "\nset key outside right\n" + plot + "\n";
  map.picture = {"convergence_time.png", script};
  return map;
}

// Numbers at their values; an axis of vectors, maps or texts by its values'
// places, each tick named by its value.
std::optional<Picture> heatMap(const fs::path& dir, const std::string& title, const std::map<long, Row>& rows,
                               const std::string& xcol, const AxisValues& xaxis, const std::string& ycol,
                               const AxisValues& yaxis) {
  struct Cell {
    int met = 0, not_met = 0, not_judged = 0, runs = 0;
  };
  std::map<std::pair<double, double>, Cell> cells;
  std::vector<double> xs, ys;
  for (const auto& [i, r] : rows) {
    const auto x = placeOf(r, xcol, xaxis), y = placeOf(r, ycol, yaxis);
    if (!x || !y) continue;
    Cell& c = cells[{*x, *y}];
    const VerdictClass v = verdictClass(r);
    c.met += v.met;
    c.not_met += v.key.rfind("not_met", 0) == 0;
    c.not_judged += v.key == "not_judged";
    ++c.runs;
    xs.push_back(*x);
    ys.push_back(*y);
  }
  if (cells.empty()) return std::nullopt;
  // An axis of values that are not numbers: its column holds the place, and
  // a last column the value itself (what the tick names).
  util::OutputStream out(dir / "heat_map.csv");
  out << xcol << "," << ycol << ",met_fraction,runs,met,not_met,not_judged"
      << (xaxis.numeric ? "" : "," + csvQuoted(xcol + " value"))
      << (yaxis.numeric ? "" : "," + csvQuoted(ycol + " value")) << "\n";
  const auto valueAt = [](const AxisValues& axis, double place) {
    return axis.numeric ? std::string() : "," + csvQuoted(axis.texts.at(static_cast<size_t>(place)));
  };
  for (const auto& [xy, c] : cells)
    out << num(xy.first) << "," << num(xy.second) << "," << num(double(c.met) / c.runs) << "," << c.runs
        << "," << c.met << "," << c.not_met << "," << c.not_judged << valueAt(xaxis, xy.first)
        << valueAt(yaxis, xy.second) << "\n";
  std::string script = header("heat_map.png", title + ": fraction of runs whose verdict is met") +
                       "set xlabel " + gnuplotString(xcol) + " noenhanced\nset ylabel " +
                       gnuplotString(ycol) +
                       " noenhanced\nset cbrange [0:1]\nset cblabel 'fraction met (verdict)'\n"
                       "set palette defined (0 '#b2182b', 0.5 '#fdae61', 1 '#2166ac')\nset key off\n";
  if (!xaxis.numeric)
    script += namedTics("x", xaxis.texts);
  else if (wantsLog(xs))
    script += "set logscale x\n";
  if (!yaxis.numeric)
    script += namedTics("y", yaxis.texts);
  else if (wantsLog(ys))
    script += "set logscale y\n";
  script +=
      "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n"
      "plot 'heat_map.csv' skip 1 using 1:2:3 with points pt 5 ps 3 palette\n";
  return Picture{"heat_map.png", script};
}

std::optional<Picture> marginMap(const fs::path& dir, const std::string& title,
                                 const std::map<long, Row>& rows) {
  std::map<double, std::pair<int, int>> by_margin;  // met, runs
  for (const auto& [i, r] : rows)
    if (const auto m = numberOf(r, "gain_margin")) {
      auto& c = by_margin[*m];
      c.first += verdictClass(r).met;
      ++c.second;
    }
  if (by_margin.empty()) return std::nullopt;
  util::OutputStream out(dir / "margin.csv");
  out << "gain_margin,met_fraction,runs\n";
  for (const auto& [m, c] : by_margin)
    out << num(m) << "," << num(double(c.first) / c.second) << "," << c.second << "\n";
  return Picture{
      "margin.png",
      header("margin.png", title + ": the continuous-time condition against what was observed") +
          "set xlabel 'smallest margin of the evaluated continuous-time conditions (> 0: all hold)'\n"
          "set ylabel 'fraction of runs whose verdict is met'\nset yrange [-0.05:1.05]\n"
          "set arrow from 0, graph 0 to 0, graph 1 nohead dt 2\nset key off\n"
          "plot 'margin.csv' skip 1 using 1:2 with points pt 7 ps 1.2\n"};
}

// Per rate, over `size` (the swept initial-state norm, or ||x(0)||): the
// largest below which every run met the metric, and the largest that met it.
std::optional<Picture> regionMap(const fs::path& dir, const std::string& title,
                                 const std::map<long, Row>& rows, const std::string& size) {
  const std::string rate = "plant.publish_rate";
  std::map<double, std::vector<std::pair<double, bool>>> by_rate;
  for (const auto& [i, r] : rows) {
    const auto f = numberOf(r, rate), x = numberOf(r, size);
    if (f && x) by_rate[*f].push_back({*x, verdictClass(r).met});
  }
  if (by_rate.size() < 2) return std::nullopt;
  util::OutputStream out(dir / "region_vs_rate.csv");
  out << "rate,all_met_below,largest_met,runs\n";
  // A rate where no run met the metric has no region: drawn as a cross below
  // the smallest initial state swept, so that it is not silently missing; one
  // where some run of the smallest size missed it has no "every run below":
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
                                   "2 lw 2 title 'no run met the metric'"
                                 : "";
  if (any_partial)
    crosses +=
        ", \\\n     'region_smallest_failed.csv' skip 1 using 1:2 with points pt 11 ps 2 lw 2 title "
        "'a run of the smallest size did not meet it'";
  return Picture{
      "region_vs_rate.png",
      header("region_vs_rate.png", title + ": where runs met the metric, against the controller rate") +
          "set logscale xy\nset xlabel 'controller rate, plant.publish_rate [Hz]' noenhanced\n"
          "set ylabel " +
          gnuplotString(axisTitle(size)) +
          " noenhanced\nset key top left box opaque\n"
          "plot 'region_vs_rate.csv' skip 1 using 1:2 with linespoints lw 2 pt 7 title "
          "'every run from below met the metric (verdict)', \\\n"
          "     '' skip 1 using 1:3 with linespoints lw 2 pt 6 dt 2 title 'largest that met it'" +
          crosses + "\n"};
}

}  // namespace

VerdictClass verdictClass(const Row& row) {
  const std::string verdict = textOf(row, "verdict");
  if (verdict == "met") return {"met", "met", true};
  if (verdict == "NOT met") {
    const std::string kind = textOf(row, "verdict_kind").substr(0, 40);
    if (kind.empty()) return {"not_met", "NOT met", false};
    std::string key = "not_met_", words;
    for (const char c : kind) {
      const bool plain =
          std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c));
      key += plain ? c : '_';
      words += c == '_' ? ' ' : c;
    }
    return {key, "NOT met: " + words, false};
  }
  if (verdict == "not judged") return {"not_judged", "not judged", false};
  if (textOf(row, "status") == "failed")
    return {"failed", "failed: no verdict (the run could not be made)", false};
  return {"no_verdict", "no verdict (a row from before verdicts)", false};
}

SweepMapFiles writeSweepMapFiles(const std::string& out_dir, const SweepPlan& plan,
                                 const std::map<long, Row>& rows) {
  const fs::path dir = fs::path(out_dir) / "maps";
  util::makeOutputDirectories(dir.string());
  // A class's file of an earlier drawing, not drawn now, is not left beside the new ones.
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if ((name.rfind("convergence_", 0) == 0 && e.path().extension() == ".csv") || name == "diverged.csv" ||
        name == "not_converged.csv")
      fs::remove(e.path(), ec);
  }
  const std::string title = fs::path(plan.spec.file).stem().string();
  SweepMapFiles maps;
  std::vector<Picture> pictures;
  // Parameter columns a map can use: not a norm axis's direction index.
  std::vector<std::string> axes;
  for (const std::string& c : plan.param_columns)
    if (c.size() < 10 || c.compare(c.size() - 10, 10, ".direction") != 0) axes.push_back(c);
  std::map<std::string, AxisValues> values;
  for (const std::string& a : axes) values[a] = valuesOf(rows, a);
  // The convergence map's x: the axis swept over the most values (the first
  // of equals), numbers or not; its points coloured by the first other axis
  // of 2 to 8 values. One axis: a line through the median times too.
  std::string xcol, group;
  for (const std::string& a : axes)
    if (xcol.empty() || values[a].distinct() > values[xcol].distinct()) xcol = a;
  for (const std::string& a : axes)
    if (a != xcol && values[a].distinct() >= 2 && values[a].distinct() <= 8) {
      group = a;
      break;
    }
  // The axes that vary: an axis of one value is no map's axis unless the
  // sweep file names it (maps.heat_map).
  std::vector<std::string> varying;
  for (const std::string& a : axes)
    if (values[a].distinct() >= 2) varying.push_back(a);
  std::optional<ConvergenceMap> convergence;
  if (!xcol.empty())
    convergence = convergenceMap(dir, title, rows, xcol, values[xcol], group, varying.size() <= 1);
  if (convergence) {
    pictures.push_back(convergence->picture);
    maps.convergence_axis = xcol;
    maps.convergence_classes = convergence->classes;
  } else {
    maps.not_drawn.push_back("convergence_time.png: no finished run has a value of " +
                             (xcol.empty() ? std::string("an axis") : xcol));
  }
  std::vector<std::string> heat, constant;
  for (const std::string& a : axes)
    if (values[a].distinct() < 2) constant.push_back(oneValue(a, values[a]));
  if (plan.spec.heat_map.size() == 2) {  // as the file asks, an axis of one value too: said so
    heat = plan.spec.heat_map;
    for (size_t k = 0; k < 2; ++k) {
      const AxisValues v = valuesOf(rows, heat[k]);
      if (v.distinct() == 1)
        maps.notes.push_back("heat_map.png: " + oneValue(heat[k], v) +
                             ", yet maps.heat_map names it: every point is in one " +
                             (k == 0 ? "column" : "row"));
    }
  } else if (axes.size() < 2) {
    maps.not_drawn.push_back("heat_map.png: the sweep has " + std::to_string(axes.size()) +
                             (axes.size() == 1 ? " axis" : " axes") +
                             "; a heat map needs two (maps.heat_map names them)");
  } else if (varying.size() >= 2) {
    heat = {varying[0], varying[1]};
    if (heat[0] != axes[0] || heat[1] != axes[1]) {
      std::string why;
      for (const std::string& c : constant) why += (why.empty() ? "" : "; ") + c;
      maps.notes.push_back("heat_map.png: drawn over " + heat[0] + " and " + heat[1] +
                           ", the first two axes that vary (" + why + ")");
    }
  } else {
    std::string why;
    for (size_t k = 0; k < constant.size(); ++k)
      why += (k == 0 ? "" : k + 1 == constant.size() ? " and " : ", ") + constant[k];
    maps.not_drawn.push_back(
        "heat_map.png: " + why +
        (varying.empty() ? "; no axis varies, and a heat map needs two that do"
                         : "; only " + varying[0] + " varies, and convergence_time.png is drawn against it"));
  }
  if (heat.size() == 2) {
    if (auto p =
            heatMap(dir, title, rows, heat[0], valuesOf(rows, heat[0]), heat[1], valuesOf(rows, heat[1]))) {
      pictures.push_back(*p);
      maps.heat_map_axes = heat;
    } else {
      maps.not_drawn.push_back("heat_map.png: no finished run has a value of both " + heat[0] + " and " +
                               heat[1]);
    }
  }
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
    if (a.size() > 5 && a.compare(a.size() - 5, 5, ".norm") == 0 && values[a].distinct() > 1) {
      size = a;
      break;
    }
  if (auto p = regionMap(dir, title, rows, size))
    pictures.push_back(*p);
  else
    maps.not_drawn.push_back("region_vs_rate.png: plant.publish_rate is not swept over two values or more");
  for (const Picture& p : pictures) {
    maps.pngs.push_back(p.png);
    maps.scripts.push_back(p.script);
  }
  return maps;
}

SweepMaps drawSweepMaps(const std::string& out_dir, const SweepPlan& plan, const std::map<long, Row>& rows) {
  const SweepMapFiles files = writeSweepMapFiles(out_dir, plan, rows);
  const fs::path dir = fs::path(out_dir) / "maps";
  std::string all;
  for (const std::string& why : files.not_drawn) all += "# not drawn: " + why + "\n";
  for (const std::string& note : files.notes) all += "# note: " + note + "\n";
  for (const std::string& script : files.scripts) all += script + "\n";
  util::writeOutputFile((dir / "maps.gp").string(), all);
  SweepMaps maps;
  maps.not_drawn = files.not_drawn;
  maps.notes = files.notes;
  maps.plots = drawPictures(dir.string(), files.pngs, files.scripts);
  return maps;
}

}  // namespace lagrange::tools
