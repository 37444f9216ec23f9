#pragma once
/// @file
/// The key table (config/key_table.hpp) as text for people: the range
/// sentence of a row, and docs/configuration.md's table of keys.

#include <string>

#include "config/key_table.hpp"

namespace lagrange::config {

/// " Range: from 0 to 1 s (why)." for a key whose row states only its own
/// range, " Ranges: `a`, `b` ...; `c` ..." for a row describing several keys
/// (robot.links' items); "" for a key without a number.
std::string rangeSentence(const KeyInfo& row);

/// docs/configuration.md's table of keys: one row per key with a type, the
/// ranges of the keys it describes appended to its meaning.
std::string keyReferenceMarkdown();

}  // namespace lagrange::config
