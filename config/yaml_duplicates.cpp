#include "config/yaml_duplicates.hpp"

#include <map>
#include <vector>

#include "config/scenario.hpp"
#include "config/yaml_reader.hpp"

namespace lagrange::config {

namespace {
struct Pending {
  YAML::Node node;
  std::string path;  // dotted, as the readers name keys ("" for the top level)
};

std::string lineNumber(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? "?" : std::to_string(mark.line + 1);
}
}  // namespace

void rejectDuplicateKeys(const YAML::Node& root, const std::string& source) {
  // Iterative, so that deep nesting cannot overflow the stack.
  std::vector<Pending> stack{{root, ""}};
  long visited = 0;
  while (!stack.empty()) {
    Pending current = std::move(stack.back());
    stack.pop_back();
    if (++visited > kMaxYamlNodes)
      throw ConfigError("config: " + source + ": the YAML tree has more than " +
                        std::to_string(kMaxYamlNodes) +
                        " nodes (aliases expanded); expected a scenario of at most that many");
    if (current.node.IsSequence()) {
      for (std::size_t i = 0; i < current.node.size(); ++i)
        stack.push_back({current.node[i], current.path + "[" + std::to_string(i) + "]"});
    } else if (current.node.IsMap()) {
      std::map<std::string, YAML::Node> seen;
      for (const auto& entry : current.node) {
        const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : flowYaml(entry.first);
        const std::string path = current.path.empty() ? key : current.path + "." + key;
        const auto [first, inserted] = seen.emplace(key, entry.first);
        if (!inserted)
          throw ConfigError("config: " + source + ": duplicate key '" + path + "' at line " +
                            lineNumber(entry.first) + " (first at line " + lineNumber(first->second) +
                            "); expected each key once in a map");
        stack.push_back({entry.second, path});
      }
    }
  }
}

}  // namespace lagrange::config
