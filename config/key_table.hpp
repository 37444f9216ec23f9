#pragma once
/// @file
/// Every key a scenario file may hold, described once: its type, default,
/// range and meaning. From this one table come the known-key lists the
/// section readers reject unknown keys with (keysUnder), the range every
/// number read is checked against (config/key_ranges.hpp: rangeOf), the key
/// reference `lagrange keys` prints and docs/configuration.md's table
/// (config/key_reference.hpp; a test fails when the file differs).
///
/// A key is named as the docs name it: list items as [i]
/// ("robot.links[i].mass"), map entries by a capital placeholder
/// ("faults.channels.NAME.drop"). What each key does to a run is in the code
/// that reads it (config/*_sections.cpp); adding a key is a row here and its
/// reading and writing there.

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "config/key_ranges.hpp"

namespace lagrange::config {

struct KeyInfo {
  std::string key;                ///< dotted, as above
  std::string type;               ///< the docs' type cell; "" for a key described in another key's row
  std::string default_text;       ///< Markdown: "`1000`", "required", "none"
  std::string meaning;            ///< Markdown, without the range (added from `range`)
  std::optional<KeyRange> range;  ///< every number has one
  /// "" for a key every scenario may hold; else the variant of its section
  /// it belongs to: "sine" / "free_motion" (reference.type), "paper" /
  /// "external" (controller.type). "registered" marks the baselines' own
  /// gains (lp, ld, lambda), here only for their ranges and docs: a
  /// registered controller's keys come from its registration
  /// (config/controller_params.hpp), not from keysUnder.
  std::string variant;
  /// The row that describes it when that is another key's (the items of
  /// robot.links in robot.links'); "" for its own row.
  std::string described_in;
};

/// The table, in the order of docs/configuration.md.
const std::vector<KeyInfo>& keyTable();

/// The keys directly below `section` ("plant" -> physics_step, publish_rate,
/// max_rate; "" -> the top-level keys; "robot.links[i]" -> length, com, ...)
/// that hold in `variant`: those of no variant and those of `variant`.
/// @throws std::logic_error when no key is under `section` (a reader's typo).
std::set<std::string> keysUnder(const std::string& section, const std::string& variant = "");

}  // namespace lagrange::config
