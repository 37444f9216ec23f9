#pragma once
/// @file
/// What an unknown scenario key most likely meant, for the readers' errors
/// (MapReader, config/yaml_reader.hpp) -- the same for a YAML file, `--set`
/// and the Python keywords (which become `--set`):
///   - a near miss of a known key at the same place: the same but for case,
///     `_` or `-` (`Kd`, `Publish_Rate`), or a small spelling difference
///     (`comand`, `physics_stp`): "did you mean kd?";
///   - a key students guess (`controller.rate`, `dt`): the key that means it
///     ("the control rate is plant.publish_rate [Hz] ...").
/// The table of guesses is in key_hints.cpp.

#include <map>
#include <set>
#include <string>
#include <vector>

namespace lagrange::config {

/// The keys of `known` that `unknown` is a near miss of, the nearest first
/// (several when equally near), or none. Keys of one or two letters (`kp`,
/// `a`) match by case, `_` and `-` only: `ki` is no misspelling of `kd`.
std::vector<std::string> nearMisses(const std::string& unknown, const std::set<std::string>& known);

/// The keys students guess, by their key-table names ("controller.rate",
/// "dt"), each with what it means ("the control rate is plant.publish_rate ...").
const std::map<std::string, std::string>& keyGuesses();

/// What a guessed key means, by its key-table name ("controller.rate" ->
/// "the control rate is plant.publish_rate [Hz] ..."), or "" for a key that
/// is no known guess.
std::string guessedKeyMeaning(const std::string& table_key);

/// "; the control rate is ..." for a guessed key, else "; did you mean kd?"
/// (or "kd or kp?") for a near miss of `known`, else "". `key` is the key as
/// written, `table_key` its key-table name (config/key_ranges.hpp: rangeKey).
std::string unknownKeyHint(const std::string& key, const std::string& table_key,
                           const std::set<std::string>& known);

/// Whether the key table (config/key_table.hpp) has `table_key`, in any
/// variant of its section, or keys below it ("robot.urdf").
bool isTableKey(const std::string& table_key);

}  // namespace lagrange::config
