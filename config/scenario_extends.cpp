#include "config/scenario_extends.hpp"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "config/input_file.hpp"
#include "config/scenario.hpp"
#include "config/yaml_duplicates.hpp"

namespace lagrange::config {

namespace {

namespace fs = std::filesystem;

// The most files one chain may hold: far past any real use, short of a
// stack a hostile chain of generated files could exhaust.
constexpr size_t kMaxChain = 32;

YAML::Node parseRoot(const std::string& yaml_text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError("config: " + source + ": malformed YAML at line " + std::to_string(e.mark.line + 1) +
                      ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  if (root.IsNull())
    throw ConfigError(
        "config: " + source +
        ": no keys (the file is empty or only comments); expected a map of keys at the top level");
  if (!root.IsMap())
    throw ConfigError("config: " + source + ": expected a map of keys at the top level, got a " +
                      (root.IsSequence() ? "list" : "single value"));
  rejectDuplicateKeys(root, source);
  return root;
}

// `over` merged onto a copy of `base`: maps key by key, anything else
// replaced; a map whose `type` changes (controller, reference) is another
// kind of section, and replaced whole: no key of the old kind stays.
YAML::Node merged(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  const YAML::Node base_type = base["type"], over_type = over["type"];
  if (base_type.IsDefined() && over_type.IsDefined() && base_type.IsScalar() && over_type.IsScalar() &&
      base_type.Scalar() != over_type.Scalar())
    return YAML::Clone(over);
  YAML::Node out = YAML::Clone(base);
  for (const auto& entry : over) {
    const std::string key = entry.first.as<std::string>();
    out[key] = out[key].IsDefined() ? merged(out[key], entry.second) : YAML::Clone(entry.second);
  }
  return out;
}

// A relative path a base file gives, made absolute from its folder, so that
// it means what it meant there whatever folder the extending file is in.
void anchorPaths(YAML::Node& root, const fs::path& folder) {
  const auto anchor = [&](YAML::Node section, const char* key) {
    if (!section.IsDefined() || !section.IsMap()) return;
    YAML::Node value = section[key];
    if (value.IsScalar() && !value.Scalar().empty() && fs::path(value.Scalar()).is_relative())
      section[key] = fs::absolute(folder / value.Scalar()).lexically_normal().string();
  };
  const YAML::Node robot = root["robot"];
  if (robot.IsDefined() && robot.IsMap()) anchor(robot["urdf"], "file");
  // A program from outside (controller or plant): its folder, and its
  // program when the first word is a path (a name is looked up on PATH).
  for (const char* name : {"controller", "plant"}) {
    YAML::Node section = root[name];
    if (!section.IsDefined() || !section.IsMap()) continue;
    anchor(section, "working_directory");
    YAML::Node command = section["command"];
    if (command.IsDefined() && command.IsSequence() && command.size() > 0 && command[0].IsScalar()) {
      const std::string program = command[0].Scalar();
      if (program.find('/') != std::string::npos && fs::path(program).is_relative())
        command[0] = fs::absolute(folder / program).lexically_normal().string();
    }
  }
}

YAML::Node resolve(YAML::Node root, const std::string& source, const fs::path& folder,
                   std::vector<std::string>& chain, std::vector<std::string>& texts) {
  const YAML::Node extends = root["extends"];
  if (!extends.IsDefined()) return root;
  if (!extends.IsScalar() || extends.Scalar().empty())
    throw ConfigError("config: " + source + ": extends: expected the path of another scenario file, e.g. " +
                      "extends: rigid_2dof.yaml (relative to this file's folder)");
  if (folder.empty())
    throw ConfigError("config: " + source + ": extends: '" + extends.Scalar() +
                      "' cannot be resolved here (a scenario that is not read from a file); expected a "
                      "scenario without extends");
  // Absolute: a base named from the working directory ("b.yaml") has a
  // folder of its own (not the empty one), for its own extends and paths.
  const fs::path base_path = fs::absolute(folder / extends.Scalar()).lexically_normal();
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(base_path, ec);
  const std::string key = ec ? base_path.string() : canonical.string();
  if (std::find(chain.begin(), chain.end(), key) != chain.end()) {
    std::string cycle;
    for (const std::string& file : chain) cycle += file + " -> ";
    throw ConfigError("config: " + source + ": extends: a cycle: " + cycle + key +
                      "; expected a chain of files that ends in one without extends");
  }
  if (chain.size() >= kMaxChain)
    throw ConfigError("config: " + source + ": extends: more than " + std::to_string(kMaxChain) +
                      " files in one chain; expected a shorter chain");
  chain.push_back(key);
  const FileText file =
      readRegularFile(base_path.string(), kMaxScenarioBytes, "a YAML scenario file to extend");
  if (!file.error.empty()) throw ConfigError("config: " + source + ": extends: " + file.error);
  texts.push_back(file.text);
  YAML::Node base = resolve(parseRoot(file.text, base_path.string()), base_path.string(),
                            base_path.parent_path(), chain, texts);
  // Only a base in another folder has paths to anchor (the resolved text of
  // a same-folder chain stays as it was, whether named relatively or not:
  // hosts of one run compare it, config.resolved.yaml shows it).
  if (base_path.parent_path() != (fs::absolute(folder) / "f").lexically_normal().parent_path())
    anchorPaths(base, base_path.parent_path());
  // A plant section without a type is the simulated plant's: one that says
  // `type: external` replaces it whole, as a controller of another type does.
  if (YAML::Node plant = base["plant"]; plant.IsDefined() && plant.IsMap() && !plant["type"].IsDefined())
    plant["type"] = "simulated";
  root.remove("extends");
  YAML::Node out = merged(base, root);
  // A command starts, by default, in the folder of the file that gave it:
  // one from the base (this file gives none, nor a folder) in the base's --
  // not the extending file's, where its relative arguments are not.
  for (const char* name : {"controller", "plant"}) {
    const YAML::Node own = root[name], from_base = base[name];
    const bool own_command = own.IsDefined() && own.IsMap() && own["command"].IsDefined();
    if (!own_command && from_base.IsDefined() && from_base.IsMap() && from_base["command"].IsDefined() &&
        out[name].IsMap() && !out[name]["working_directory"].IsDefined())
      out[name]["working_directory"] = fs::absolute(base_path.parent_path()).lexically_normal().string();
  }
  return out;
}

fs::path folderOf(const std::string& source) {
  const fs::path p(source);
  std::error_code ec;
  return fs::is_regular_file(p, ec) ? p.parent_path() : fs::path();
}

}  // namespace

ScenarioTree loadScenarioTree(const std::string& path) {
  const FileText file = readRegularFile(path, kMaxScenarioBytes, "a YAML scenario file");
  if (!file.error.empty()) throw ConfigError("config: " + file.error);
  return parseScenarioTree(file.text, path);
}

ScenarioTree parseScenarioTree(const std::string& yaml_text, const std::string& source) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(source, ec);
  ScenarioTree tree;
  tree.chain = {ec ? source : canonical.string()};
  tree.texts = {yaml_text};
  fs::path folder = folderOf(source);
  if (folder.empty() && fs::is_regular_file(source, ec)) folder = ".";
  tree.root = resolve(parseRoot(yaml_text, source), source, folder, tree.chain, tree.texts);
  return tree;
}

std::optional<KeyPlace> keyPlace(const ScenarioTree& tree, const std::string& key) {
  std::vector<std::string> names;
  for (size_t start = 0;;) {
    const size_t dot = key.find('.', start);
    std::string name = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    name = name.substr(0, name.find('['));  // "kp[1]": the list's key
    if (name.empty()) return std::nullopt;
    names.push_back(name);
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  // Only a key the merged tree holds: a base's key that a change of the
  // section's type dropped is not where a "missing" came from.
  // (Walked with reset and const lookups: a Node's operator= would write
  // into the tree, and a non-const [] may add the key.)
  YAML::Node at = tree.root;
  for (const std::string& name : names) {
    const YAML::Node& here = at;
    if (!here.IsMap() || !here[name].IsDefined()) return std::nullopt;
    at.reset(here[name]);
  }
  for (size_t i = 0; i < tree.texts.size() && i < tree.chain.size(); ++i) {
    YAML::Node node;
    try {
      node.reset(YAML::Load(tree.texts[i]));
    } catch (const YAML::Exception&) {
      return std::nullopt;
    }
    std::optional<YAML::Mark> mark;
    for (const std::string& name : names) {
      mark.reset();
      if (!node.IsMap()) break;
      YAML::Node next;
      for (const auto& entry : node)
        if (entry.first.IsScalar() && entry.first.Scalar() == name) {
          mark = entry.first.Mark();
          next.reset(entry.second);
          break;
        }
      if (!mark) break;
      node.reset(next);
    }
    if (mark && !mark->is_null()) return KeyPlace{i, mark->line + 1};
  }
  return std::nullopt;
}

ScenarioTree parseRecordedScenarioTree(const std::string& yaml_text, const std::string& source) {
  ScenarioTree tree;
  tree.chain = {source};
  tree.root = parseRoot(yaml_text, source);
  if (static_cast<const YAML::Node&>(tree.root)["extends"].IsDefined())
    throw ConfigError("config: " + source +
                      ": extends: a recorded scenario is the resolved one a run wrote, which has no "
                      "extends; a reader of a log opens no file the log names");
  return tree;
}

}  // namespace lagrange::config
