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
  /// it belongs to: "sine" / "free_motion" (reference.type), "external"
  /// (controller.type), or one a file outside config registers with its rows
  /// (registerKeyRows): "paper" (controller/paper_section.cpp), "registered"
  /// (controller/baselines.cpp: the baselines' own gains lp, ld, lambda, here
  /// only for their ranges and docs -- a registered controller's keys come
  /// from its registration, config/controller_params.hpp, not from keysUnder).
  std::string variant;
  /// The row that describes it when that is another key's (the items of
  /// robot.links in robot.links'); "" for its own row.
  std::string described_in;
};

/// The table, in the order of docs/configuration.md; the registered rows
/// (registerKeyRows) follow the controller's own.
const std::vector<KeyInfo>& keyTable();

/// Adds the rows of keys a section outside config owns (the paper's
/// controllers' gains, stages and filter starts: controller/paper_section.cpp),
/// from a static initialiser: rows of the new `variant`, which messages call
/// "a key of <description>". @throws std::logic_error once keyTable() has
/// been read, or when the variant is taken.
void registerKeyRows(const std::string& variant, const std::string& description, std::vector<KeyInfo> rows);

/// What a variant is, for messages ("reference.type free_motion only").
/// @throws std::logic_error for a variant nobody declared.
const std::string& variantDescription(const std::string& variant);

/// What the table's rows are made of, for registerKeyRows' callers too.
namespace keyrow {
/// A key with its own row.
KeyInfo row(std::string key, std::string type, std::string default_text, std::string meaning);
KeyInfo row(std::string key, std::string type, std::string default_text, std::string meaning, KeyRange range);
/// A key of a list item or map entry, or a registered controller's gain,
/// described in the row of `described_in`.
KeyInfo inside(std::string key, std::string described_in, KeyRange range);
/// `k`, a key of that variant of its section only (KeyInfo::variant).
KeyInfo only(std::string variant, KeyInfo k);
KeyRange angle();       ///< multi-turn angles [rad]
KeyRange rate();        ///< rates [rad/s]
KeyRange gain();        ///< gains: positive, far below where gain x error x rate overflows
KeyRange largeState();  ///< filter and chain states
}  // namespace keyrow

/// The keys directly below `section` ("plant" -> physics_step, publish_rate,
/// max_rate; "" -> the top-level keys; "robot.links[i]" -> length, com, ...)
/// that hold in `variant`: those of no variant and those of `variant`.
/// @throws std::logic_error when no key is under `section` (a reader's typo).
std::set<std::string> keysUnder(const std::string& section, const std::string& variant = "");

}  // namespace lagrange::config
