#pragma once
/// @file
/// Strict, path-aware reading of a YAML map: every key read is remembered, so
/// finish() can reject the ones nobody asked for (unknown keys are errors,
/// never ignored), and every error names the dotted key, the value, what was
/// expected and the line. Every number read is checked against its key's
/// range (config/key_ranges.hpp) when the section is finished, after the
/// reader's own checks.

#include <yaml-cpp/yaml.h>

#include <Eigen/Dense>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "util/enum_names.hpp"

namespace lagrange::config {

class MapReader {
 public:
  /// @throws ConfigError if node is not a map.
  MapReader(YAML::Node node, std::string path);

  bool has(const std::string& key) const;
  YAML::Node child(const std::string& key);  ///< marks the key as read; may be undefined

  double number(const std::string& key);                   ///< required
  double number(const std::string& key, double fallback);  ///< optional
  double positive(const std::string& key);
  double positive(const std::string& key, double fallback);
  int integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);  ///< optional: true or false
  std::string text(const std::string& key);
  std::string text(const std::string& key, const std::string& fallback);

  /// A per-joint vector: a list of exactly n numbers, or one number applied
  /// to every joint when allow_scalar. Required.
  Eigen::VectorXd vector(const std::string& key, int n, bool allow_scalar, bool positive_only);
  std::optional<Eigen::VectorXd> optionalVector(const std::string& key, int n, bool allow_scalar,
                                                bool positive_only);

  /// One of an enum's names (util/enum_names.hpp); an unknown one fails with
  /// "unknown WHAT 'value'; expected: a, b or c". Required, or `fallback`.
  template <class E, std::size_t N>
  E choice(const std::string& key, const util::EnumName<E> (&names)[N], const std::string& what) {
    const std::string value = text(key);
    if (const std::optional<E> e = util::enumFrom(names, value)) return *e;
    fail(key, "unknown " + what + " '" + value + "'; expected: " + util::choicesOf(names));
  }
  template <class E, std::size_t N>
  E choice(const std::string& key, const util::EnumName<E> (&names)[N], const std::string& what, E fallback) {
    return has(key) ? choice(key, names, what) : fallback;
  }

  MapReader map(const std::string& key);  ///< required sub-map

  /// @throws ConfigError naming the first number read out of its key's range,
  /// else the first unknown key, what it most likely meant (a near miss,
  /// config/key_hints.hpp: "did you mean kd?") and the known ones -- those of
  /// the section's type when it has one.
  void finish(const std::set<std::string>& known) const;

  /// The keys of the map, in file order (for maps keyed by name).
  std::vector<std::string> keys() const;

  std::string keyPath(const std::string& key) const;

  /// @throws ConfigError "KEY: WHAT (line N)"; for an absent key of which the
  /// map holds an unknown near miss ("Kd" for kd), that key named instead:
  /// "Kd: unknown key (line N); did you mean kd? kd is missing".
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  double finiteNumber(const std::string& key);  ///< required; no range check
  /// Notes v when it is outside its key's range (config/key_ranges.hpp), for
  /// finish() to report: the section reader's own checks, which come between
  /// the read and finish(), say more ("a SCHED_FIFO priority from 1 to 99, or
  /// 0 for the normal scheduler") and come first. `entry` prefixes the
  /// message ("entry 2: ") for a list.
  void checkRange(const std::string& key, double v, const std::string& entry = "");
  std::string ofType(const std::set<std::string>& known) const;

  YAML::Node node_;
  std::vector<std::pair<std::string, std::string>> out_of_range_;  ///< key, message
  std::string path_;
  /// The keys this section's reader asked about: none of them is a near miss
  /// of another key it finds missing (config/key_hints.hpp), whatever the table holds.
  mutable std::set<std::string> asked_;
};

/// " (line N)" for a node with a position, "" otherwise.
std::string lineOf(const YAML::Node& node);

/// The node as one line of YAML flow style ("{kp: [1, 2]}"), as --set takes it.
std::string flowYaml(const YAML::Node& node);

}  // namespace lagrange::config
