#pragma once
/// @file
/// Reading what `lagrange sweep` writes, for its tests: files as text, the
/// table without its one varying column, the rows each shard appended.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace lagrange::testing {

inline std::string readText(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The table without its wall_time column, the one column that differs from
// run to run (docs/sweeps.md). Fields hold no commas in these tests' sweeps.
inline std::string tableWithoutWallTime(const std::string& out) {
  std::ifstream in(out + "/sweep.csv");
  std::string header, line, table;
  std::getline(in, header);
  std::vector<std::string> names;
  for (size_t start = 0, end; start <= header.size(); start = end + 1) {
    end = header.find(',', start);
    if (end == std::string::npos) end = header.size();
    names.push_back(header.substr(start, end - start));
  }
  const auto wall = std::find(names.begin(), names.end(), "wall_time") - names.begin();
  if (static_cast<size_t>(wall) == names.size()) return "(no wall_time column in " + out + "/sweep.csv)";
  table = header + "\n";
  while (std::getline(in, line)) {
    size_t start = 0;
    for (long i = 0; i < wall; ++i) start = line.find(',', start) + 1;
    const size_t end = line.find(',', start);
    table += line.substr(0, start) + line.substr(end + 1) + "\n";
  }
  return table;
}

// Every row line in OUT/rows, by index: how many times each was written.
inline std::map<long, int> rowLines(const std::string& out) {
  std::map<long, int> lines;
  const std::regex index(R"(^\{"index":(\d+),)");
  for (const auto& f : std::filesystem::directory_iterator(out + "/rows")) {
    std::ifstream in(f.path());
    std::smatch m;
    for (std::string line; std::getline(in, line);)
      if (std::regex_search(line, m, index)) ++lines[std::stol(m[1])];
  }
  return lines;
}

}  // namespace lagrange::testing
