#pragma once
/// @file
/// `extends: other.yaml` in a scenario file: the other file (relative to
/// this one's folder; it may extend a third) is read first and this file's
/// keys are merged over it -- maps key by key, any other value (a list, a
/// number) replaced whole, and a map whose `type` changes (a controller of
/// another kind) replaced whole, the rule `--set` follows too when it changes
/// a type (config/scenario.cpp; docs/configuration.md, "Changing a section's
/// type") -- before `--set` applies. A cycle is refused,
/// naming the chain. A relative path a base file gives (`robot.urdf`,
/// `controller.working_directory`) stays relative to the base file's folder.
/// The resolved scenario (config.resolved.yaml) holds the merged result and
/// no `extends`.

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>

namespace lagrange::config {

#include <vector>

/// A scenario's YAML with its `extends` chain merged in.
struct ScenarioTree {
  YAML::Node root;
  /// The files read, the scenario's first, then each one it extends. More
  /// than one: the merge has lost the values' line numbers (yaml-cpp keeps
  /// none in a merged tree), so errors name the chain instead.
  std::vector<std::string> chain;
  /// Each file's text, in the chain's order: an error about a key names the
  /// line of the file that wrote it (keyPlace).
  std::vector<std::string> texts;
};

/// Where a key of the merged tree was written: the first file of the chain
/// that writes it (the scenario's own first: its values win), and the
/// key's line there (1-based).
struct KeyPlace {
  size_t file = 0;  ///< into ScenarioTree::chain
  int line = 0;
};

/// `key` is a dotted path as errors name it ("plant.bogus",
/// "controller.kp[1]": the list's key). None when the merged tree does not
/// hold it (a missing key: a base's dropped by a change of type is not
/// where it came from) or no file writes it, or a file's text does not parse.
std::optional<KeyPlace> keyPlace(const ScenarioTree& tree, const std::string& key);

/// The scenario file at `path` with its `extends` chain merged in.
/// @throws ConfigError naming the file, the chain and what was expected.
ScenarioTree loadScenarioTree(const std::string& path);

/// The tree of scenario text `yaml_text` read from `source` (a path, or a
/// name such as "LOG:SCENARIO"), with an `extends` resolved against the
/// folder of `source` when it has one.
ScenarioTree parseScenarioTree(const std::string& yaml_text, const std::string& source);

/// The tree of a recorded scenario (a log's SCENARIO, a run folder's
/// config.resolved.yaml): the resolved scenario a run wrote, read as data.
/// Nothing is looked up on disk and an `extends` is refused -- a resolved
/// scenario has none, and one in a log would have its reader open a file the
/// log names. @throws ConfigError naming `source`.
ScenarioTree parseRecordedScenarioTree(const std::string& yaml_text, const std::string& source);

}  // namespace lagrange::config
