#include "config/yaml_reader.hpp"

#include <cmath>
#include <map>

#include "config/key_hints.hpp"
#include "config/key_ranges.hpp"
#include "config/key_table.hpp"
#include "config/scenario.hpp"

namespace lagrange::config {

std::string flowYaml(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

std::string lineOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return "";
  return " (line " + std::to_string(mark.line + 1) + ")";
}

namespace {
std::string show(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return "nothing";
}

bool toNumber(const YAML::Node& node, double& out) {
  if (!node.IsScalar()) return false;
  try {
    out = node.as<double>();
  } catch (const YAML::Exception&) {
    return false;
  }
  return std::isfinite(out);
}
}  // namespace

MapReader::MapReader(YAML::Node node, std::string path) : node_(node), path_(std::move(path)) {
  if (!node_.IsMap())
    throw ConfigError("config: " + (path_.empty() ? std::string("the file") : path_) +
                      ": expected a map of keys, got " + show(node_) + lineOf(node_));
}

std::vector<std::string> MapReader::keys() const {
  std::vector<std::string> out;
  for (const auto& entry : node_) out.push_back(entry.first.as<std::string>());
  return out;
}

std::string MapReader::keyPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

namespace {
// The line of a map's entry: its key's, or, for a key --set made (which has
// none), its value's "(line 1)", which the --set's error replaces with the
// option (config/scenario.cpp) right after the key it names.
std::string lineOfKey(const std::pair<YAML::Node, YAML::Node>& entry) {
  const std::string key = lineOf(entry.first);
  return key.empty() ? lineOf(entry.second) : key;
}

// A key of `node` that is a near miss of the absent `key` (config/key_hints.hpp)
// and no key the table or this section's reader knows: "Kd" when kd is
// missing. Its error says more than kd's ("missing"), which it causes.
YAML::Node nearMissOf(const YAML::Node& node, const std::string& key, const std::string& path,
                      const std::set<std::string>& asked) {
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) continue;
    const std::string written = entry.first.Scalar();
    if (asked.count(written) != 0 || nearMisses(written, {key}).empty()) continue;
    if (isTableKey(rangeKey(path.empty() ? written : path + "." + written))) continue;
    return entry.first;
  }
  return YAML::Node();
}
}  // namespace

void MapReader::fail(const std::string& key, const std::string& what) const {
  if (!has(key)) {
    const YAML::Node written = nearMissOf(node_, key, path_, asked_);
    if (written.IsScalar())
      throw ConfigError("config: " + keyPath(written.Scalar()) + ": unknown key" +
                        lineOfKey({written, node_[written.Scalar()]}) + "; did you mean " + key + "? " +
                        keyPath(key) + " is missing");
  }
  const YAML::Node value = has(key) ? node_[key] : YAML::Node();
  const std::string where = has(key) ? lineOf(value) : lineOf(node_);
  throw ConfigError("config: " + keyPath(key) + ": " + what + where);
}

bool MapReader::has(const std::string& key) const {
  asked_.insert(key);
  return node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node MapReader::child(const std::string& key) {
  asked_.insert(key);
  return node_[key];
}

double MapReader::finiteNumber(const std::string& key) {
  if (!has(key)) fail(key, "missing; expected a number");
  double v = 0.0;
  if (!toNumber(node_[key], v)) fail(key, "expected a finite number, got " + show(node_[key]));
  return v;
}

void MapReader::checkRange(const std::string& key, double v, const std::string& entry) {
  const KeyRange* range = rangeOf(keyPath(key));
  if (range == nullptr || range->contains(v)) return;
  out_of_range_.push_back({key, entry + "expected a number " + rangeText(*range) + ", got " + shortNumber(v) +
                                    (range->why.empty() ? "" : " (" + range->why + ")")});
}

double MapReader::number(const std::string& key) {
  const double v = finiteNumber(key);
  checkRange(key, v);
  return v;
}

double MapReader::number(const std::string& key, double fallback) {
  return has(key) ? number(key) : fallback;
}

double MapReader::positive(const std::string& key) {
  if (!has(key)) fail(key, "missing; expected a positive number");
  const double v = finiteNumber(key);
  if (!(v > 0.0)) fail(key, "expected a positive number, got " + show(node_[key]));
  checkRange(key, v);
  return v;
}

double MapReader::positive(const std::string& key, double fallback) {
  return has(key) ? positive(key) : fallback;
}

int MapReader::integer(const std::string& key, int fallback) {
  if (!has(key)) return fallback;
  const double v = finiteNumber(key);
  if (v != std::floor(v) || std::abs(v) > 1e9) fail(key, "expected a whole number, got " + show(node_[key]));
  checkRange(key, v);
  return static_cast<int>(v);
}

std::string MapReader::text(const std::string& key) {
  if (!has(key)) fail(key, "missing; expected a string");
  if (!node_[key].IsScalar()) fail(key, "expected a string, got " + show(node_[key]));
  return node_[key].Scalar();
}

bool MapReader::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const YAML::Node value = node_[key];
  if (value.IsScalar() && (value.Scalar() == "true" || value.Scalar() == "false"))
    return value.Scalar() == "true";
  fail(key, "expected true or false, got " + show(value));
}

std::string MapReader::text(const std::string& key, const std::string& fallback) {
  return has(key) ? text(key) : fallback;
}

Eigen::VectorXd MapReader::vector(const std::string& key, int n, bool allow_scalar, bool positive_only) {
  const std::string kind = positive_only ? "positive number" : "number";
  const std::string expected = "a list of " + std::to_string(n) + " " + kind + "s (one per joint)" +
                               (allow_scalar ? " or a single " + kind + " for every joint" : "");
  if (!has(key)) fail(key, "missing; expected " + expected);
  const YAML::Node value = node_[key];
  Eigen::VectorXd out(n);
  double x = 0.0;
  if (value.IsScalar()) {
    if (!allow_scalar || !toNumber(value, x)) fail(key, "expected " + expected + ", got " + show(value));
    if (positive_only && !(x > 0.0)) fail(key, "expected " + expected + ", got " + show(value));
    checkRange(key, x);
    out.setConstant(x);
    return out;
  }
  if (!value.IsSequence()) fail(key, "expected " + expected + ", got " + show(value));
  if (static_cast<int>(value.size()) != n)
    fail(key, "expected " + expected + ", got a list of " + std::to_string(value.size()));
  for (int i = 0; i < n; ++i) {
    if (!toNumber(value[i], x) || (positive_only && !(x > 0.0)))
      fail(key, "entry " + std::to_string(i + 1) + ": expected a " + kind + ", got " + show(value[i]));
    checkRange(key, x, "entry " + std::to_string(i + 1) + ": ");
    out(i) = x;
  }
  return out;
}

std::optional<Eigen::VectorXd> MapReader::optionalVector(const std::string& key, int n, bool allow_scalar,
                                                         bool positive_only) {
  if (!has(key)) return std::nullopt;
  return vector(key, n, allow_scalar, positive_only);
}

MapReader MapReader::map(const std::string& key) {
  if (!has(key)) fail(key, "missing; expected a map");
  if (!node_[key].IsMap()) fail(key, "expected a map, got " + show(node_[key]));
  return MapReader(node_[key], keyPath(key));
}

namespace {
// "; initial_q is a key of reference.type free_motion only" for a key the key
// table has in another variant of its section (config/key_table.hpp), "" otherwise.
std::string variantHint(const std::string& key, const std::string& key_path) {
  const std::string table_key = rangeKey(key_path);
  for (const KeyInfo& k : keyTable())
    if (k.key == table_key && !k.variant.empty())
      return "; " + key + " is a key of " + variantDescription(k.variant);
  return "";
}
}  // namespace

// " (the keys of controller type pd_plus_differenced)" for a section that
// has a type, whose keys depend on it: a key of another type is refused
// naming the type it is not a key of.
std::string MapReader::ofType(const std::set<std::string>& known) const {
  if (path_.empty() || known.count("type") == 0) return "";
  const YAML::Node type = node_["type"];
  if (!type.IsDefined() || !type.IsScalar()) return "";
  return " (the keys of " + path_ + " type " + type.Scalar() + ")";
}

void MapReader::finish(const std::set<std::string>& known) const {
  if (!out_of_range_.empty()) fail(out_of_range_.front().first, out_of_range_.front().second);
  for (const auto& entry : node_) {
    const std::string key = entry.first.Scalar();
    if (known.count(key) == 0) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      const std::string hint = unknownKeyHint(key, rangeKey(keyPath(key)), known);
      throw ConfigError("config: " + keyPath(key) + ": unknown key" + lineOfKey(entry) + hint +
                        (hint.empty() || hint.back() != '?' ? "; " : " ") + "expected one of: " + list +
                        ofType(known) + variantHint(key, keyPath(key)));
    }
  }
}

}  // namespace lagrange::config
