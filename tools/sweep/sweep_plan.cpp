#include "tools/sweep/sweep_plan.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "config/yaml_reader.hpp"
#include "model/reference.hpp"
#include "tools/sweep/sweep_files.hpp"
#include "tools/sweep/sweep_random.hpp"
#include "util/error.hpp"
#include "util/fnv1a.hpp"
#include "util/number_text.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;
using config::ConfigError;

inline constexpr util::EnumName<SweepDesign> kDesignNames[] = {
    {SweepDesign::kGrid, "grid"}, {SweepDesign::kRandom, "random"}, {SweepDesign::kHalton, "halton"}};
inline constexpr util::EnumName<AxisScale> kScaleNames[] = {{AxisScale::kLinear, "linear"},
                                                            {AxisScale::kLog, "log"}};

// "config: KEY: what" from the readers, as "sweep FILE: KEY: what".
[[noreturn]] void rethrow(const std::string& file, const ConfigError& e) {
  std::string what = e.what();
  if (what.rfind("config: ", 0) == 0) what = what.substr(8);
  throw ConfigError("sweep " + file + ": " + what);
}

std::string vectorText(const Eigen::VectorXd& v) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) s += (i ? ", " : "") + util::exactText(v[i]);
  return s + "]";
}

AxisRange readRange(config::MapReader m, bool grid) {
  AxisRange r;
  r.from = m.number("from");
  r.to = m.number("to");
  r.scale = m.choice("scale", kScaleNames, "scale", AxisScale::kLinear);
  m.finish({"from", "to", "count", "scale"});
  r.count = m.integer("count", grid ? 0 : 1);
  if (grid && r.count < 1) m.fail("count", "expected a whole number >= 1 of points (a grid needs count)");
  if (!std::isfinite(r.from) || !std::isfinite(r.to)) m.fail("from", "expected finite bounds");
  if (r.scale == AxisScale::kLog && (r.from <= 0 || r.to <= 0))
    m.fail("from", "a log scale needs from > 0 and to > 0");
  return r;
}

// The value at fraction f in [0, 1] of a range; the ends are exact.
double at(const AxisRange& r, double f) {
  if (f <= 0) return r.from;
  if (f >= 1) return r.to;
  if (r.scale == AxisScale::kLinear) return r.from + f * (r.to - r.from);
  // In decades: a range of powers of ten gives them exactly (10^0 = 1, not 1.0000000000000009).
  return std::pow(10.0, std::log10(r.from) + f * (std::log10(r.to) - std::log10(r.from)));
}

}  // namespace

std::string scenarioDigest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return util::fnv1a64Hex(bytes);
}

namespace {

double gridPoint(const AxisRange& r, int i) {
  return r.count == 1 ? r.from : at(r, double(i) / (r.count - 1));
}

SweepAxis readAxis(config::MapReader m, bool grid) {
  m.finish({"key", "values", "range", "norm", "directions"});
  SweepAxis a;
  a.key = m.text("key");
  const int kinds = m.has("values") + m.has("range") + m.has("norm");
  if (kinds != 1) m.fail("key", "axis '" + a.key + "': expected exactly one of values, range or norm");
  if (m.has("values")) {
    const YAML::Node list = m.child("values");
    if (!list.IsSequence() || list.size() == 0)
      m.fail("values", "axis '" + a.key + "' is empty; expected a list of at least one value");
    for (const YAML::Node& v : list) a.values.push_back(config::flowYaml(v));
  }
  if (m.has("range")) a.range = readRange(m.map("range"), grid);
  if (m.has("norm")) {
    a.norm = readRange(m.map("norm"), grid);
    if (a.norm->from < 0 || a.norm->to < 0) m.fail("norm", "expected norms >= 0");
    a.directions = m.integer("directions", 1);
    if (a.directions < 1) m.fail("directions", "expected a whole number >= 1");
  } else if (m.has("directions")) {
    m.fail("directions", "applies to a norm axis only");
  }
  return a;
}

// Points of an axis in a grid.
long gridSize(const SweepAxis& a) {
  if (!a.values.empty()) return static_cast<long>(a.values.size());
  if (a.range) return a.range->count;
  return static_cast<long>(a.norm->count) * a.directions;
}

// A row's choice on one axis: a parameter text, or (norm axes) a radius and a direction.
struct AxisPick {
  std::string text;  // values, range (left empty when not asked for)
  double radius = 0;
  long direction = 0;
  long choice = -1;  // the point of a grid's axis or the value of a list; -1: a draw from a range
};

AxisPick gridPick(const SweepAxis& a, long i, bool text) {
  if (!a.values.empty()) return {text ? a.values[static_cast<size_t>(i)] : "", 0, 0, i};
  if (a.range) return {text ? util::exactText(gridPoint(*a.range, static_cast<int>(i))) : "", 0, 0, i};
  return {"", gridPoint(*a.norm, static_cast<int>(i / a.directions)), i % a.directions, i};
}

// f in [0, 1) -> the axis's draw in a random or Halton design.
AxisPick drawnPick(const SweepAxis& a, double f, long row, bool text) {
  if (!a.values.empty()) {
    const auto n = a.values.size();
    const size_t i = std::min(n - 1, static_cast<size_t>(f * static_cast<double>(n)));
    return {text ? a.values[i] : "", 0, 0, static_cast<long>(i)};
  }
  if (a.range) return {text ? util::exactText(at(*a.range, f)) : "", 0, 0, -1};
  return {"", at(*a.norm, f), row, -1};
}

// Centre of a norm axis's vectors: the reference's initial state for the
// arm's initial state (so the norm is the initial tracking error), else 0.
Eigen::VectorXd centreOf(const std::string& key, const config::Scenario& s) {
  if (key == "initial_state.q" || key == "initial_state.qdot") {
    const model::ReferenceSample r0 = model::Reference(s.reference).evaluate(0.0, 1);
    return key == "initial_state.q" ? r0.q() : r0.qd();
  }
  return Eigen::VectorXd::Zero(s.dof());
}

}  // namespace

SweepSpec readSweepSpec(const std::string& path) {
  SweepSpec spec;
  spec.file = fs::absolute(path).lexically_normal().string();
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError("sweep " + path + ": cannot read the file; expected a readable sweep YAML file");
  } catch (const YAML::Exception& e) {
    throw ConfigError("sweep " + path + ": malformed YAML: " + e.msg + " at line " +
                      std::to_string(e.mark.line + 1));
  }
  try {
    config::MapReader m(root, "");
    m.finish({"scenario", "set", "design", "samples", "seed", "axes", "maps",
              "simulate_sampled_data"});  // a misspelt key first
    const std::string scenario = m.text("scenario");
    spec.scenario_path = (fs::path(spec.file).parent_path() / scenario).lexically_normal().string();
    if (!fs::is_regular_file(spec.scenario_path))
      m.fail("scenario", "no such file '" + spec.scenario_path +
                             "'; expected a scenario YAML file (relative to the sweep file)");
    spec.scenario_digest = scenarioDigest(spec.scenario_path);
    if (m.has("set")) {
      const YAML::Node set = m.child("set");
      if (!set.IsMap()) m.fail("set", "expected a map of scenario keys to values, e.g. {duration: 5}");
      for (const auto& kv : set) spec.set.push_back(kv.first.Scalar() + "=" + config::flowYaml(kv.second));
    }
    spec.design = m.choice("design", kDesignNames, "design", SweepDesign::kGrid);
    const bool grid = spec.design == SweepDesign::kGrid;
    if (!grid) {
      spec.samples = m.integer("samples", 0);
      if (spec.samples < 1)
        m.fail("samples", "expected the number of runs (>= 1) of a random or halton design");
    } else if (m.has("samples")) {
      m.fail("samples", "a grid runs every combination of its axes; samples applies to random and halton");
    }
    const double seed = m.number("seed", 1);
    if (seed < 0 || seed != std::floor(seed) || seed > 9.0e15) m.fail("seed", "expected a whole number >= 0");
    spec.seed = static_cast<std::uint64_t>(seed);
    spec.simulate_sampled_data = m.boolean("simulate_sampled_data", false);
    const YAML::Node axes = m.child("axes");
    if (!axes.IsSequence() || axes.size() == 0)
      m.fail("axes", "expected a list of at least one axis ({key, values | range | norm})");
    for (size_t i = 0; i < axes.size(); ++i)
      spec.axes.push_back(readAxis(config::MapReader(axes[i], "axes[" + std::to_string(i) + "]"), grid));
    if (m.has("maps")) {
      config::MapReader maps = m.map("maps");
      const YAML::Node heat = maps.child("heat_map");
      if (heat.IsDefined()) {
        if (!heat.IsSequence() || heat.size() != 2)
          maps.fail("heat_map", "expected two parameter columns, [X, Y]");
        for (const YAML::Node& k : heat) spec.heat_map.push_back(k.Scalar());
      }
      maps.finish({"heat_map"});
    }
  } catch (const ConfigError& e) {
    rethrow(path, e);
  }
  return spec;
}

// A planned sweep's rows, decoded from their index. The overrides of a row
// are the spec's `set` and its axes' values, except for a norm axis's
// vectors, centre + r u: the centre comes from the scenario the other axes
// make (its reference and size), read once per combination of them while
// planning and kept here as an index into the distinct centres.
struct SweepRows::Design {
  struct Centres {
    int dof = 0;
    std::vector<Eigen::VectorXd> by_axis;  // a norm axis's centre; empty for the others
  };
  SweepSpec spec;
  long rows = 0;
  HaltonSequence halton;
  bool has_norm = false;
  // The combination of the axes that are not norm axes: each row's own
  // (`by_row`: a draw from a range, or more combinations than rows), or the
  // axes' choices in mixed radix, `stride` per axis (0 for a norm axis).
  bool by_row = false;
  std::vector<long> stride;
  long combinations = 0;
  std::vector<std::int32_t> centre_of;  // with a norm axis: per combination, its index in `centres`
  std::vector<Centres> centres;

  Design(SweepSpec s, long n)
      : spec(std::move(s)), rows(n), halton(static_cast<int>(spec.axes.size()), spec.seed) {
    for (const SweepAxis& a : spec.axes) has_norm = has_norm || a.norm.has_value();
    const bool grid = spec.design == SweepDesign::kGrid;
    stride.assign(spec.axes.size(), 0);
    combinations = 1;
    for (size_t i = spec.axes.size(); i-- > 0 && !by_row;) {  // the last axis varies fastest
      const SweepAxis& a = spec.axes[i];
      if (a.norm) continue;
      const long points = grid ? gridSize(a) : a.values.empty() ? -1 : static_cast<long>(a.values.size());
      stride[i] = combinations;
      by_row = points < 0 || points > rows || (combinations *= points) > rows;
    }
    if (by_row) combinations = rows;
  }

  // Each axis's choice for row `index`; the parameter texts when `text`.
  std::vector<AxisPick> picks(long index, bool text) const {
    std::vector<AxisPick> picks(spec.axes.size());
    long rest = index;
    for (size_t i = spec.axes.size(); i-- > 0;) {  // grid: the last axis varies fastest
      const SweepAxis& a = spec.axes[i];
      if (spec.design == SweepDesign::kGrid) {
        const long n = gridSize(a);
        picks[i] = gridPick(a, rest % n, text);
        rest /= n;
      } else {
        const double f = spec.design == SweepDesign::kHalton ? halton.at(index, static_cast<int>(i))
                                                             : uniform01(spec.seed, kStreamDesign + i, index);
        picks[i] = drawnPick(a, f, index, text);
      }
    }
    return picks;
  }

  long combination(long index, const std::vector<AxisPick>& picks) const {
    if (by_row) return index;
    long c = 0;
    for (size_t i = 0; i < picks.size(); ++i) c += stride[i] * (spec.axes[i].norm ? 0 : picks[i].choice);
    return c;
  }

  // `set`, then the axes that are not norm axes: what the row's scenario is read with.
  std::vector<std::string> fixedOverrides(const std::vector<AxisPick>& picks) const {
    std::vector<std::string> overrides = spec.set;
    for (size_t i = 0; i < spec.axes.size(); ++i)
      if (!spec.axes[i].norm) overrides.push_back(spec.axes[i].key + "=" + picks[i].text);
    return overrides;
  }

  SweepRow row(long index) const {
    const std::vector<AxisPick> picks = this->picks(index, true);
    SweepRow row;
    row.index = index;
    row.overrides = fixedOverrides(picks);
    const Centres* centre = nullptr;
    if (has_norm) {
      const std::int32_t id = centre_of.at(static_cast<size_t>(combination(index, picks)));
      if (id < 0) throw RuntimeFault("sweep: row " + std::to_string(index) + " was not planned");
      centre = &centres.at(static_cast<size_t>(id));
    }
    for (size_t i = 0; i < spec.axes.size(); ++i) {
      const SweepAxis& a = spec.axes[i];
      if (!a.norm) {
        row.params.push_back(picks[i].text);
        continue;
      }
      const Eigen::VectorXd u =
          unitDirection(spec.seed, kStreamDirection + i, picks[i].direction, centre->dof);
      row.overrides.push_back(a.key + "=" + vectorText(centre->by_axis[i] + picks[i].radius * u));
      row.params.push_back(util::exactText(picks[i].radius));
      row.params.push_back(std::to_string(picks[i].direction));
    }
    return row;
  }
};

SweepRow SweepRows::operator[](std::size_t i) const {
  if (i < static_cast<std::size_t>(count_)) {
    if (!design_)
      throw RuntimeFault("sweep: the rows of a plan read from plan.json are read from the file, not held");
    return design_->row(static_cast<long>(i));
  }
  return listed_.at(i - static_cast<std::size_t>(count_));
}

std::size_t SweepRows::heldBytes() const {
  std::size_t bytes = sizeof *this;
  for (const SweepRow& r : listed_) {
    bytes += sizeof r;
    for (const auto* texts : {&r.params, &r.overrides})
      for (const std::string& t : *texts) bytes += sizeof t + t.capacity();
  }
  if (design_) {
    bytes += sizeof *design_ + design_->stride.capacity() * sizeof(long) +
             design_->centre_of.capacity() * sizeof(std::int32_t);
    for (const Design::Centres& c : design_->centres) {
      bytes += sizeof c;
      for (const Eigen::VectorXd& v : c.by_axis)
        bytes += sizeof v + static_cast<std::size_t>(v.size()) * sizeof(double);
    }
  }
  return bytes;
}

SweepPlan planSweep(const SweepSpec& spec) {
  SweepPlan plan;
  plan.spec = spec;
  for (const SweepAxis& a : spec.axes) {
    if (a.norm) {
      plan.param_columns.push_back(a.key + ".norm");
      plan.param_columns.push_back(a.key + ".direction");
    } else {
      plan.param_columns.push_back(a.key);
    }
  }
  for (const std::string& k : spec.heat_map)
    if (std::find(plan.param_columns.begin(), plan.param_columns.end(), k) == plan.param_columns.end())
      throw ConfigError("sweep " + spec.file + ": maps.heat_map: '" + k +
                        "' is not a parameter column; expected one of the axes' columns");

  long rows = 1;
  if (spec.design == SweepDesign::kGrid) {
    for (const SweepAxis& a : spec.axes) {
      rows *= gridSize(a);
      if (rows > kMaxSweepRows)
        throw ConfigError("sweep " + spec.file + ": the grid has more than " + std::to_string(kMaxSweepRows) +
                          " runs; expected fewer points per axis, or a random or halton design");
    }
  } else {
    rows = spec.samples;
    if (rows > kMaxSweepRows)
      throw ConfigError("sweep " + spec.file + ": samples: more than " + std::to_string(kMaxSweepRows) +
                        " runs; expected fewer, or several sweeps");
  }

  // Every combination of the axes that are not norm axes is read once, at
  // its first row: its scenario, and with a norm axis the centres of the
  // vectors (kept, shared by the combinations with the same ones) and the
  // row with them.
  auto design = std::make_shared<SweepRows::Design>(spec, rows);
  std::vector<bool> seen(static_cast<size_t>(design->has_norm ? 0 : design->combinations), false);
  if (design->has_norm) design->centre_of.assign(static_cast<size_t>(design->combinations), -1);
  std::map<std::vector<std::uint64_t>, std::int32_t> centre_ids;  // by dof and the centres' bits
  for (long index = 0; index < rows; ++index) {
    const auto c = static_cast<size_t>(design->combination(index, design->picks(index, false)));
    if (design->has_norm ? design->centre_of[c] >= 0 : seen[c]) continue;
    const std::vector<std::string> overrides = design->fixedOverrides(design->picks(index, true));
    config::Scenario s;
    try {
      s = config::loadScenario(spec.scenario_path, overrides);
    } catch (const ConfigError& e) {
      throw ConfigError("sweep " + spec.file + ": run " + std::to_string(index) + " (" + [&] {
        std::string text;
        for (size_t i = spec.set.size(); i < overrides.size(); ++i)
          text += (text.empty() ? "" : ", ") + overrides[i];
        return text.empty() ? std::string("the base scenario with set") : text;
      }() + "): " + e.what());
    }
    if (!design->has_norm) {
      seen[c] = true;
      continue;
    }
    SweepRows::Design::Centres centres;
    centres.dof = s.dof();
    centres.by_axis.resize(spec.axes.size());
    std::vector<std::uint64_t> key = {static_cast<std::uint64_t>(centres.dof)};
    for (size_t i = 0; i < spec.axes.size(); ++i) {
      if (!spec.axes[i].norm) continue;
      centres.by_axis[i] = centreOf(spec.axes[i].key, s);
      for (Eigen::Index k = 0; k < centres.by_axis[i].size(); ++k) {
        std::uint64_t bits = 0;
        std::memcpy(&bits, &centres.by_axis[i][k], sizeof bits);
        key.push_back(bits);
      }
    }
    const auto [found, added] = centre_ids.emplace(key, static_cast<std::int32_t>(design->centres.size()));
    if (added) design->centres.push_back(std::move(centres));
    design->centre_of[c] = found->second;
    // The vectors are the scenario's size by construction; the first row of
    // each combination checks that its keys take them.
    try {
      config::loadScenario(spec.scenario_path, design->row(index).overrides);
    } catch (const ConfigError& e) {
      throw ConfigError("sweep " + spec.file + ": run " + std::to_string(index) + ": " + e.what());
    }
  }
  plan.rows = SweepRows(std::move(design), rows);
  return plan;
}

namespace {
// `text` with every decimal fraction (digits with a point or an exponent,
// signed, not inside a word) written as util::exactText writes its double.
// Whole numbers stay as written: a seed above 2^53 is not a double.
std::string shortestNumbers(const std::string& text) {
  const auto digit = [&text](size_t i) {
    return i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]));
  };
  const auto word = [&text](size_t i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    return std::isalnum(c) || c == '_' || c == '.';
  };
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const bool starts = digit(i) || ((text[i] == '-' || text[i] == '.') && digit(i + 1));
    if (starts && (i == 0 || !word(i - 1))) {
      char* end = nullptr;
      const double value = std::strtod(text.c_str() + i, &end);
      const size_t length = static_cast<size_t>(end - (text.c_str() + i));
      const std::string token = text.substr(i, length);
      const bool fraction = token.find_first_of(".eE") != std::string::npos;
      if (length > 0 && fraction && !(i + length < text.size() && word(i + length))) {
        out += util::exactText(value);
        i += length;
        continue;
      }
    }
    out += text[i++];
  }
  return out;
}
}  // namespace

bool samePlanText(const std::string& a, const std::string& b) {
  return a == b || shortestNumbers(a) == shortestNumbers(b);
}

std::string planHeaderJson(const SweepPlan& plan) {
  nlohmann::ordered_json head;
  head["sweep_file"] = plan.spec.file;
  head["scenario"] = plan.spec.scenario_path;
  head["scenario_digest"] = plan.spec.scenario_digest;
  head["columns"] = plan.param_columns;
  head["heat_map"] = plan.spec.heat_map;
  if (plan.spec.simulate_sampled_data) head["simulate_sampled_data"] = true;  // absent: the plans of before
  head["rows"] = plan.rows.size();
  return head.dump();
}

std::string planRowJson(const SweepRow& row) {
  nlohmann::ordered_json j;
  j["index"] = row.index;
  j["params"] = row.params;
  j["overrides"] = row.overrides;
  return j.dump();
}

void forEachPlanLine(const SweepPlan& plan, const std::function<void(const std::string&)>& on_line) {
  on_line(planHeaderJson(plan));
  for (const SweepRow& r : plan.rows) on_line(planRowJson(r));
}

std::string planJson(const SweepPlan& plan) {
  std::string text;
  forEachPlanLine(plan, [&text](const std::string& line) { text += line + "\n"; });
  return text;
}

namespace {
// A line parsed with its nesting bounded (sweep_files.hpp), or why not.
nlohmann::ordered_json planLine(const std::string& at, const std::string& text) {
  std::string why;
  std::optional<nlohmann::ordered_json> j = parseSweepJson(text, why);
  if (!j) throw BadInput(at + ": " + why);
  return std::move(*j);
}

[[noreturn]] void notAPlan(const std::string& source, const std::exception& e) {
  throw ConfigError(source + ": not a sweep plan written by lagrange sweep (" + e.what() + ")");
}
}  // namespace

SweepPlan planHeaderFromJson(const std::string& line, const std::string& source) {
  SweepPlan plan;
  try {
    const auto head = planLine("its header", line);
    plan.spec.file = head.at("sweep_file").get<std::string>();
    plan.spec.scenario_path = head.at("scenario").get<std::string>();
    plan.spec.scenario_digest = head.at("scenario_digest").get<std::string>();
    plan.param_columns = head.at("columns").get<std::vector<std::string>>();
    plan.spec.heat_map = head.at("heat_map").get<std::vector<std::string>>();
    plan.spec.simulate_sampled_data =
        head.value("simulate_sampled_data", false);  // a plan from before the key: off
    const auto rows = head.at("rows").get<size_t>();
    if (rows > static_cast<size_t>(kMaxSweepRows))
      throw BadInput("its header gives " + std::to_string(rows) + " rows; a sweep has at most " +
                     std::to_string(kMaxSweepRows));
    plan.rows = SweepRows::counted(static_cast<long>(rows));
  } catch (const std::exception& e) {
    notAPlan(source, e);
  }
  return plan;
}

SweepRow planRowFromJson(const std::string& line, long index, const std::string& source) {
  try {
    const std::string at = "row line " + std::to_string(index + 2);
    const auto j = planLine(at, line);
    const auto& i = j.at("index");
    // Row i is the plan's row i: an index is a place in the table, nothing else.
    if (!i.is_number_integer() || i.get<long long>() != static_cast<long long>(index))
      throw BadInput(at + ": index " + i.dump() + "; expected " + std::to_string(index));
    return {index, j.at("params").get<std::vector<std::string>>(),
            j.at("overrides").get<std::vector<std::string>>()};
  } catch (const std::exception& e) {
    notAPlan(source, e);
  }
}

}  // namespace lagrange::tools
