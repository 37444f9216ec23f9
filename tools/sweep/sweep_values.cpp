#include "tools/sweep/sweep_values.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <optional>

#include "util/number_text.hpp"

namespace lagrange::tools {

namespace {

// Deeper than this a value stays its text: a row is read back with its
// nesting bounded (sweep_files.hpp, 32 levels), and no scenario key is a
// list of lists of lists.
constexpr int kMaxTypedDepth = 16;

// A plain scalar as the scenario reads it: true/false as config's boolean()
// reads them, a number as the row's numbers were always read (strtod, all
// of the text, finite).
nlohmann::ordered_json plainScalar(const std::string& text) {
  if (text == "true" || text == "false") return text == "true";
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (!text.empty() && end && *end == '\0' && std::isfinite(v)) return v;
  return text;
}

std::optional<nlohmann::ordered_json> typedNode(const YAML::Node& node, int depth) {
  if (depth > kMaxTypedDepth) return std::nullopt;
  switch (node.Type()) {
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      return nlohmann::ordered_json();
    case YAML::NodeType::Scalar:  // "!" is a quoted scalar: a string, whatever it reads as
      return node.Tag() == "!" ? nlohmann::ordered_json(node.Scalar()) : plainScalar(node.Scalar());
    case YAML::NodeType::Sequence: {
      nlohmann::ordered_json list = nlohmann::ordered_json::array();
      for (const YAML::Node& item : node) {
        std::optional<nlohmann::ordered_json> v = typedNode(item, depth + 1);
        if (!v) return std::nullopt;
        list.push_back(std::move(*v));
      }
      return list;
    }
    case YAML::NodeType::Map: {
      nlohmann::ordered_json map = nlohmann::ordered_json::object();  // in the order written
      for (const auto& kv : node) {
        std::optional<nlohmann::ordered_json> v = typedNode(kv.second, depth + 1);
        if (!v || !kv.first.IsScalar()) return std::nullopt;
        map[kv.first.Scalar()] = std::move(*v);
      }
      return map;
    }
  }
  return std::nullopt;
}

bool isNumberList(const nlohmann::ordered_json& v) {
  if (!v.is_array() || v.empty()) return false;
  for (const auto& x : v)
    if (!x.is_number()) return false;
  return true;
}

}  // namespace

nlohmann::ordered_json typedParam(const std::string& yaml_text) {
  try {
    if (std::optional<nlohmann::ordered_json> v = typedNode(YAML::Load(yaml_text), 0)) return std::move(*v);
  } catch (const YAML::Exception&) {  // not YAML: kept as it is
  }
  return yaml_text;
}

void typeOldParams(nlohmann::ordered_json& row, const std::vector<std::string>& param_columns) {
  for (const std::string& column : param_columns) {
    const auto found = row.find(column);
    if (found == row.end() || !found->is_string()) continue;
    const std::string& text = found->get_ref<const std::string&>();
    const bool quoted =
        text.size() >= 2 && (text.front() == '"' || text.front() == '\'') && text.back() == text.front();
    const bool yaml_text = text == "true" || text == "false" || quoted ||
                           (!text.empty() && (text.front() == '[' || text.front() == '{'));
    if (!yaml_text) continue;
    nlohmann::ordered_json typed = typedParam(text);
    if (typed.is_array() || typed.is_object() || typed.is_boolean() || (quoted && typed.is_string()))
      *found = std::move(typed);
  }
}

std::vector<CsvParamColumn> csvParamColumns(const std::vector<std::string>& param_columns,
                                            const std::map<long, nlohmann::ordered_json>& rows) {
  std::vector<CsvParamColumn> out;
  for (const std::string& column : param_columns) {
    // The length every value's list has: 0 until a value is seen, -1 once
    // one is not a list of numbers or its length differs.
    long length = 0;
    for (const auto& [index, row] : rows) {
      const auto v = row.find(column);
      if (v == row.end() || v->is_null()) continue;
      const long n = isNumberList(*v) ? static_cast<long>(v->size()) : -1;
      if (n < 0 || (length != 0 && n != length)) {
        length = -1;
        break;
      }
      length = n;
    }
    if (length <= 0) {
      out.push_back({column, column, -1});
      continue;
    }
    for (long i = 0; i < length; ++i)
      out.push_back({column + "[" + std::to_string(i) + "]", column, static_cast<int>(i)});
  }
  return out;
}

std::string csvField(const nlohmann::ordered_json& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_float()) return util::exactText(v.get<double>());
  const std::string text = v.is_string() ? v.get<std::string>() : v.dump();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return quoted + "\"";
}

}  // namespace lagrange::tools
