#include "tools/report/csv_rows.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace lagrange::tools {

CsvRows::CsvRows(const std::string& path) : in_(path) {
  std::string header;
  if (!std::getline(in_, header)) return;
  std::istringstream fields(header);
  std::string name;
  for (int i = 0; std::getline(fields, name, ','); ++i) {
    columns_.emplace(name, i);  // a repeated name: its first column
    fields_ = static_cast<size_t>(i) + 1;
  }
}

int CsvRows::column(const std::string& name) const {
  const auto it = columns_.find(name);
  return it == columns_.end() ? -1 : it->second;
}

bool CsvRows::next(std::vector<double>& row) {
  if (!std::getline(in_, line_)) return false;
  row.assign(fields_, std::nan(""));
  const char* p = line_.c_str();
  for (size_t i = 0; i < row.size(); ++i) {
    char* end = nullptr;
    const double value = std::strtod(p, &end);
    if (end != p) row[i] = value;
    while (*end != '\0' && *end != ',') ++end;  // an empty or unreadable field stays NaN
    if (*end == '\0') break;
    p = end + 1;
  }
  return true;
}

}  // namespace lagrange::tools
