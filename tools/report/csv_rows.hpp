#pragma once
/// @file
/// Reads back, row by row as numbers, a CSV file the report wrote: the
/// derived tables and the plots' ranges come from the same files the user
/// gets, so they describe exactly what is plotted. An empty field is NaN.

#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace lagrange::tools {

class CsvRows {
 public:
  /// Opens `path`; ok() is false when it is missing or has no header line.
  explicit CsvRows(const std::string& path);
  bool ok() const { return !columns_.empty(); }
  /// Each column's 0-based index in a row, by its header name.
  const std::map<std::string, int>& columns() const { return columns_; }
  /// The index of `name`, or -1.
  int column(const std::string& name) const;
  /// The next row into `row` (one number per header column); false at the end.
  bool next(std::vector<double>& row);

 private:
  std::ifstream in_;
  std::map<std::string, int> columns_;
  size_t fields_ = 0;  ///< the header's fields (more than columns_ when a name repeats)
  std::string line_;
};

}  // namespace lagrange::tools
