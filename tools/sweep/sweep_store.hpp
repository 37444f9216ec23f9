#pragma once
/// @file
/// `lagrange sweep`, what is on disk. OUT/plan.json is the plan; each shard
/// appends its finished rows, one JSON line each, to OUT/rows/shard-K-of-N.jsonl
/// (one write per row, so a killed shard leaves every finished row whole and
/// at most one partial line, which is dropped); the table (OUT/sweep.csv and
/// OUT/sweep.jsonl, rows in index order) is made from the union of those
/// files, by the local sweep at its end or by `lagrange sweep collect`.

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/sweep/sweep_plan.hpp"

namespace lagrange::tools {

/// Finished rows in OUT/rows/*.jsonl, by index (a row in two files -- a
/// restart with other shards cannot make one, but a copied file could -- is
/// taken once).
std::map<long, nlohmann::ordered_json> readFinishedRows(const std::string& out_dir);

/// Appends rows to one shard's file, first cutting a partial last line a
/// killed writer left.
class RowWriter {
 public:
  explicit RowWriter(const std::string& path);
  ~RowWriter();
  RowWriter(const RowWriter&) = delete;
  RowWriter& operator=(const RowWriter&) = delete;
  void append(const nlohmann::ordered_json& row);  ///< one write(2) of the line

 private:
  std::string path_;
  int fd_ = -1;
};

/// Writes OUT/sweep.csv and OUT/sweep.jsonl (each to a temporary file, then
/// renamed) from the rows, in index order.
void writeSweepTable(const std::string& out_dir, const SweepPlan& plan,
                     const std::map<long, nlohmann::ordered_json>& rows);

/// The table's CSV header: index, the parameter columns, the result columns.
std::vector<std::string> tableColumns(const SweepPlan& plan);

}  // namespace lagrange::tools
