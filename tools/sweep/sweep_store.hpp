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

/// What OUT/rows holds for a plan: the rows of the plan, each once, and what
/// was refused.
struct FinishedRows {
  std::map<long, nlohmann::ordered_json> rows;  ///< by index, each in 0 .. plan rows - 1 (when kept)
  std::vector<bool> done;                       ///< per row of the plan: in OUT/rows
  long count = 0;                               ///< rows done
  long refused = 0;                             ///< lines and files refused
  /// The first few refusals, each naming the file, the line, the value and
  /// what was expected.
  std::vector<std::string> refusals;
};

/// Finished rows in OUT/rows/*.jsonl for a plan of `plan_rows` rows, read
/// without trusting the folder (tools/sweep/sweep_files.hpp): a file that is
/// a link, not a regular file, or larger than plan_rows lines of
/// kMaxSweepLineBytes can be is refused whole; a line too long, not JSON,
/// nested too deep, not an object, or whose index is not a whole number from
/// 0 to plan_rows - 1 is refused; a row already read (in this file or an
/// earlier one, in name order) is refused again. A last line without its
/// newline (a shard killed mid-write) is dropped, not refused. Without
/// `keep_rows` only `done` and `count` are filled (a shard, a restart):
/// a bit a row of the plan, and 4 bytes a row while reading. A kept row
/// written before its axis values were typed has them typed
/// (`param_columns`, the plan's: sweep_values.hpp typeOldParams).
FinishedRows readFinishedRows(const std::string& out_dir, long plan_rows, bool keep_rows = true,
                              const std::vector<std::string>& param_columns = {});

/// Appends rows to one shard's file, first cutting a partial last line a
/// killed writer left.
class RowWriter {
 public:
  /// Opens (or creates) the file, never through a link planted in its place
  /// (its target would be cut and appended to): util::UnsafeOutputPath then,
  /// naming it, as for a directory or a device there.
  explicit RowWriter(const std::string& path);
  ~RowWriter();
  RowWriter(const RowWriter&) = delete;
  RowWriter& operator=(const RowWriter&) = delete;
  void append(const nlohmann::ordered_json& row);  ///< one write(2) of the line

 private:
  std::string path_;
  int fd_ = -1;
};

/// Writes OUT/sweep.csv and OUT/sweep.jsonl (both to temporary files, then
/// both renamed) from the rows, in index order. The CSV's columns: index,
/// the parameter columns (an axis of lists of n numbers as n columns
/// KEY[0] .. KEY[n-1]: sweep_values.hpp csvParamColumns), the result columns.
void writeSweepTable(const std::string& out_dir, const SweepPlan& plan,
                     const std::map<long, nlohmann::ordered_json>& rows);

}  // namespace lagrange::tools
