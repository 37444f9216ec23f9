#pragma once
/// @file
/// `lagrange sweep`, its plan: a sweep file (a base scenario, keys set for
/// every run, axes over scenario keys and how to sample them) read and
/// expanded into numbered rows, each the `--set` overrides of one in-process
/// run. Everything a run depends on is decided here, before any run starts,
/// from the file and its seed alone: the plan is the same on every machine
/// and for every way of splitting it into shards. docs/sweeps.md.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/scenario.hpp"

namespace lagrange::tools {

enum class SweepDesign { kGrid, kRandom, kHalton };
enum class AxisScale { kLinear, kLog };

/// `range:` or `norm:` of an axis: `count` points from `from` to `to` in a
/// grid; the bounds of the draws in a random or Halton design.
struct AxisRange {
  double from = 0.0, to = 0.0;
  int count = 1;
  AxisScale scale = AxisScale::kLinear;
};

/// One axis: exactly one of `values`, `range`, `norm`.
struct SweepAxis {
  std::string key;                  ///< a dotted scenario key, as for --set
  std::vector<std::string> values;  ///< `values:` each as YAML text
  std::optional<AxisRange> range;   ///< `range:` a number per row
  /// `norm:` a vector key set to centre + r u: r from the range, u a seeded
  /// random unit vector (centre q_d(0) for initial_state.q, q_d'(0) for
  /// initial_state.qdot, zero for any other key).
  std::optional<AxisRange> norm;
  int directions = 1;  ///< `norm` in a grid: random directions per norm value
};

struct SweepSpec {
  std::string file;           ///< the sweep file, absolute
  std::string scenario_path;  ///< the base scenario, absolute
  /// FNV-1a (64 bits, hex) of the base scenario's bytes: a restart into the
  /// same directory, or a shard, with an edited scenario is refused (files it
  /// names, such as a URDF, are not covered).
  std::string scenario_digest;
  std::vector<std::string> set;  ///< `set:` overrides of every run, KEY=VALUE
  SweepDesign design = SweepDesign::kGrid;
  long samples = 0;  ///< random and halton: rows
  std::uint64_t seed = 1;
  std::vector<SweepAxis> axes;
  std::vector<std::string> heat_map;  ///< `maps.heat_map`: two parameter columns (default: the first two)
  /// `simulate_sampled_data`: each row's run judged against the same loop at a
  /// fine rate (wiring::judgeRun; the sampled_verdict column), 24 x its cost.
  bool simulate_sampled_data = false;
};

/// One run of the sweep.
struct SweepRow {
  long index = 0;
  std::vector<std::string> params;     ///< one text per parameter column
  std::vector<std::string> overrides;  ///< `set`, then one per axis
};

/// The rows of a plan. A planned sweep holds none of them: a row is its index
/// into the design, decoded on demand (operator[], iteration) from the sweep
/// file, its seed and, with a `norm:` axis, a table of 4 bytes per
/// combination of the other axes (the centre of its vectors). Rows may also be
/// listed one by one (push_back: a plan made by hand), or only counted (a plan
/// read back from plan.json, whose rows are read from the file as they are
/// needed: sweep_plan_file.hpp).
class SweepRows {
 public:
  struct Design;  ///< how a planned sweep's rows are decoded (sweep_plan.cpp)
  SweepRows() = default;
  SweepRows(std::shared_ptr<const Design> design, long count) : design_(std::move(design)), count_(count) {}
  /// Rows counted, not held: operator[] throws.
  static SweepRows counted(long count) {
    SweepRows r;
    r.count_ = count;
    return r;
  }

  std::size_t size() const { return static_cast<std::size_t>(count_) + listed_.size(); }
  bool empty() const { return size() == 0; }
  /// Row i, decoded (or as listed). @throws RuntimeFault on counted rows.
  SweepRow operator[](std::size_t i) const;
  void push_back(SweepRow row) { listed_.push_back(std::move(row)); }
  /// What the rows hold in memory [bytes]: the design's per-combination
  /// table and centres, or the listed rows; not the sweep file's axes.
  std::size_t heldBytes() const;

  class const_iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = SweepRow;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = SweepRow;
    const_iterator(const SweepRows* rows, std::size_t i) : rows_(rows), i_(i) {}
    SweepRow operator*() const { return (*rows_)[i_]; }
    const_iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator==(const const_iterator& o) const { return i_ == o.i_; }
    bool operator!=(const const_iterator& o) const { return i_ != o.i_; }

   private:
    const SweepRows* rows_;
    std::size_t i_;
  };
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size()}; }

 private:
  std::shared_ptr<const Design> design_;
  long count_ = 0;
  std::vector<SweepRow> listed_;
};

struct SweepPlan {
  SweepSpec spec;
  std::vector<std::string> param_columns;  ///< per axis its key; a norm axis KEY.norm and KEY.direction
  SweepRows rows;
};

/// FNV-1a (64 bits) of a file's bytes, as 16 hex digits.
std::string scenarioDigest(const std::string& path);

/// Reads a sweep file. @throws config::ConfigError naming the key and what
/// was expected (unknown keys, an empty axis, a bad range).
SweepSpec readSweepSpec(const std::string& path);

/// The spec's rows, each checked: every distinct scenario the rows make is
/// read once (a value the scenario rejects is named with its axis and row),
/// and with a norm axis the first row of each with its vectors. The rows are
/// not held (SweepRows): a plan of 10 million rows takes a few bytes a
/// combination of its axes, the most a sweep may have takes at most 4 bytes
/// a row. @throws config::ConfigError.
SweepPlan planSweep(const SweepSpec& spec);

/// The plan as JSON lines, stored as OUT/plan.json: a restart compares it with
/// the plan it makes, and the shards read it. `on_line` is given the header,
/// then each row's line in order (without the newline), one at a time.
void forEachPlanLine(const SweepPlan& plan, const std::function<void(const std::string&)>& on_line);
/// The first of those lines, and a row's.
std::string planHeaderJson(const SweepPlan& plan);
std::string planRowJson(const SweepRow& row);
/// The same lines as one text, each ended by a newline (a small plan).
std::string planJson(const SweepPlan& plan);
/// The plan a plan.json header line gives, its rows counted (SweepRows::counted).
/// @throws config::ConfigError naming `source` when it is not one.
SweepPlan planHeaderFromJson(const std::string& line, const std::string& source);
/// Row `index` of a plan.json from its line. @throws config::ConfigError
/// naming `source` when the line is not that row (its index is its place).
SweepRow planRowFromJson(const std::string& line, long index, const std::string& source);
/// The most rows a sweep may have.
inline constexpr long kMaxSweepRows = 10'000'000;

/// Whether two plan.json texts are the same plan: equal but for how their
/// numbers are written (plans before 2026-11-27 wrote 17 significant digits,
/// "0.10000000000000001", where the shortest text that reads back as the
/// same double, "0.1", is written now), so a sweep started then resumes.
bool samePlanText(const std::string& a, const std::string& b);

}  // namespace lagrange::tools
