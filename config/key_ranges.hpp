#pragma once
/// @file
/// The range of every numeric key of a scenario (held in the key table,
/// config/key_table.hpp): MapReader checks each number it reads against it
/// (with the key's line in the error), docs/configuration.md states it in the
/// key's row (generated from the same table). The ranges are physically generous, so that no real
/// scenario is refused, and finite, so that nothing downstream overflows,
/// divides by almost zero or loops for ever (a gain of 1e308 overflows the
/// first product, a physics step of 1e-300 asks for 1e297 steps a sample).

#include <map>
#include <string>

namespace lagrange::config {

struct KeyRange {
  double min = 0.0;
  double max = 0.0;
  bool min_exclusive = false;  ///< "> min" (a key that must be positive with no floor of its own)
  std::string unit;            ///< "s", "Hz", "" for a pure number
  std::string why;             ///< said in the error where the bound is not obvious; "" otherwise

  bool contains(double x) const { return (min_exclusive ? x > min : x >= min) && x <= max; }
};

/// The key as the table names it: list indices as [i] ("robot.links[0].mass"
/// -> "robot.links[i].mass"), channel and process names as NAME and PROCESS
/// ("faults.channels.all.drop" -> "faults.channels.NAME.drop"), an actuator
/// initial-state row ("actuator.initial_state[2].row") as "actuator.initial_state".
std::string rangeKey(const std::string& key_path);

/// The range of a key path (as MapReader names it), or nullptr for a key that is not a number.
const KeyRange* rangeOf(const std::string& key_path);

/// Every range, by its key in the key table.
const std::map<std::string, KeyRange>& keyRanges();

/// "from 0.001 to 3600 s", "> 0 and at most 1e12", as errors and the docs say it.
std::string rangeText(const KeyRange& range);

/// A number as short text: 1e-07 -> "1e-7", 3600 -> "3600", 1e+12 -> "1e12".
std::string shortNumber(double x);

}  // namespace lagrange::config
