#pragma once
/// @file
/// `lagrange sweep`, its plan: a sweep file (a base scenario, keys set for
/// every run, axes over scenario keys and how to sample them) read and
/// expanded into numbered rows, each the `--set` overrides of one in-process
/// run. Everything a run depends on is decided here, before any run starts,
/// from the file and its seed alone: the plan is the same on every machine
/// and for every way of splitting it into shards. docs/sweeps.md.

#include <cstdint>
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

struct SweepPlan {
  SweepSpec spec;
  std::vector<std::string> param_columns;  ///< per axis its key; a norm axis KEY.norm and KEY.direction
  std::vector<SweepRow> rows;
};

/// FNV-1a (64 bits) of a file's bytes, as 16 hex digits.
std::string scenarioDigest(const std::string& path);

/// Reads a sweep file. @throws config::ConfigError naming the key and what
/// was expected (unknown keys, an empty axis, a bad range).
SweepSpec readSweepSpec(const std::string& path);

/// Expands the spec into its rows, reading every distinct scenario the rows
/// make (a value the scenario rejects is named with its axis and row).
/// @throws config::ConfigError.
SweepPlan planSweep(const SweepSpec& spec);

/// The plan as JSON text (one line per row), stored as OUT/plan.json: a
/// restart compares it with the plan it makes, and the shards read it.
std::string planJson(const SweepPlan& plan);
/// @throws config::ConfigError when `text` is not a plan.
SweepPlan planFromJson(const std::string& text, const std::string& source);

/// Whether two plan.json texts are the same plan: equal but for how their
/// numbers are written (plans before 2026-11-27 wrote 17 significant digits,
/// "0.10000000000000001", where the shortest text that reads back as the
/// same double, "0.1", is written now), so a sweep started then resumes.
bool samePlanText(const std::string& a, const std::string& b);

}  // namespace lagrange::tools
