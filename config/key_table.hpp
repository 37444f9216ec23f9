#pragma once
/// @file
/// Every key a scenario file may hold, described once: its type, default,
/// range and meaning. From this one table come the known-key lists the
/// section readers reject unknown keys with (keysUnder), the range every
/// number read is checked against (config/key_ranges.hpp: rangeOf), the key
/// reference `lagrange keys` prints and docs/configuration.md's table (a
/// test fails when the file differs from keyReferenceMarkdown()).
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
  /// "external" / "registered" (controller.type).
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
std::set<std::string> keysUnder(const std::string& section, const std::string& variant = "");

/// " Range: from 0 to 1 s (why)." for a key whose row states only its own
/// range, " Ranges: `a`, `b` ...; `c` ..." for a row describing several keys
/// (robot.links' items); "" for a key without a number.
std::string rangeSentence(const KeyInfo& row);

/// docs/configuration.md's table of keys: one row per key with a type, the
/// ranges of the keys it describes appended to its meaning.
std::string keyReferenceMarkdown();

}  // namespace lagrange::config
