// docs/configuration.md cannot drift from what the readers accept: every key
// a scenario may hold (config::keys::documentedKeys(), the same lists and
// field descriptions the readers reject unknown keys with) has its row, and
// every row names a key that exists.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "config/key_ranges.hpp"
#include "config/scenario_keys.hpp"

namespace lagrange::config {
namespace {

// Row key -> the row's whole text, for every row of the keys table (its first
// cell holds one or more keys in backticks).
std::map<std::string, std::string> documentedRows() {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/docs/configuration.md");
  std::map<std::string, std::string> rows;
  std::string line;
  const std::regex backticked("`([^`]+)`");
  while (std::getline(in, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const std::string first_cell = line.substr(1, line.find('|', 1) - 1);
    for (std::sregex_iterator it(first_cell.begin(), first_cell.end(), backticked), end; it != end; ++it)
      rows[(*it)[1]] = line;
  }
  return rows;
}

TEST(ConfigDocs, EveryKeyHasItsRow) {
  const auto rows = documentedRows();
  ASSERT_GT(rows.size(), 40u) << "the table of docs/configuration.md was not found or not parsed";
  for (const keys::DocumentedKey& key : keys::documentedKeys()) {
    const auto row = rows.find(key.row);
    if (row == rows.end()) {
      ADD_FAILURE() << "docs/configuration.md has no row for `" << key.row << "`";
      continue;
    }
    if (!key.inside.empty()) {
      EXPECT_TRUE(std::regex_search(row->second, std::regex("\\b" + key.inside + "\\b")))
          << "the row of `" << key.row << "` does not describe its key " << key.inside;
    }
  }
}

TEST(ConfigDocs, EveryRowIsAKeyTheReadersAccept) {
  std::set<std::string> known;
  for (const keys::DocumentedKey& key : keys::documentedKeys()) known.insert(key.row);
  for (const auto& [row, text] : documentedRows())
    EXPECT_EQ(known.count(row), 1u) << "docs/configuration.md documents `" << row
                                    << "`, which no reader accepts";
}

// The row that documents a key of the range table: its own, or the row of the
// list item or map entry it is inside ("robot.links[i].mass" in robot.links),
// or controller.type for the baselines' own gains.
std::string rowOfRange(const std::string& key, const std::map<std::string, std::string>& rows) {
  if (rows.count(key) > 0) return key;
  std::smatch m;
  if (std::regex_match(key, m, std::regex(R"((.*)\[i\]\.\w+)"))) return m[1];
  if (std::regex_match(key, m, std::regex(R"((faults\.channels\.NAME)\.\w+)"))) return m[1];
  if (key.rfind("controller.", 0) == 0) return "controller.type";
  return key;
}

TEST(ConfigDocs, EveryRangeIsStatedInItsRow) {
  const auto rows = documentedRows();
  for (const auto& [key, range] : keyRanges()) {
    const auto row = rows.find(rowOfRange(key, rows));
    if (row == rows.end()) {
      ADD_FAILURE() << "no row documents the range of " << key;
      continue;
    }
    EXPECT_NE(row->second.find(rangeText(range)), std::string::npos)
        << "the row of `" << row->first << "` does not state the range of " << key << ": "
        << rangeText(range);
  }
}

// A row whose type is numeric (number, vector, integer, probability) has a
// range, and so has every key of a list item or map entry.
TEST(ConfigDocs, EveryNumericKeyHasARange) {
  const auto rows = documentedRows();
  const std::regex numeric("number|vector|integer|probability");
  for (const keys::DocumentedKey& key : keys::documentedKeys()) {
    const auto row = rows.find(key.row);
    if (row == rows.end()) continue;  // EveryKeyHasItsRow says so
    const std::string type = row->second.substr(row->second.find('|', 1) + 1);
    const std::string type_cell = type.substr(0, type.find('|'));
    std::string path = key.row;
    if (!key.inside.empty())
      path = key.row + (key.row.find("NAME") != std::string::npos ? "." : "[i].") + key.inside;
    else if (!std::regex_search(type_cell, numeric))
      continue;
    EXPECT_NE(rangeOf(path), nullptr) << path << " is numeric (" << type_cell << ") and has no range";
  }
}

}  // namespace
}  // namespace lagrange::config
