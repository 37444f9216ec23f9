#pragma once
/// @file
/// `lagrange sweep`'s progress: rows counted in OUT/rows/*.jsonl as the
/// shards append them (locally or on a cluster's shared directory), shown as
/// a bar with the rate and the time left on a terminal, as a plain line every
/// 10 s otherwise.

#include <chrono>
#include <map>
#include <string>

namespace lagrange::tools {

struct RowCount {
  long rows = 0;      ///< whole lines
  long diverged = 0;  ///< of them, runs the plant stopped
};

/// Counts new bytes only: each call reads what the files gained since the last.
class RowCounter {
 public:
  explicit RowCounter(std::string out_dir) : dir_(std::move(out_dir)) {}
  RowCount count();

 private:
  std::string dir_;
  std::map<std::string, long long> offsets_;
  RowCount total_;
};

class SweepProgress {
 public:
  SweepProgress(long total, long done_at_start, bool quiet);
  void update(long done, long diverged);
  void interrupt();  ///< end a bar's line before other output
  /// Draws the final count (the bar at its end) and ends the line.
  void finish(long done, long diverged);

 private:
  void draw(long done, long diverged);
  long total_, start_done_;
  bool quiet_, tty_;
  bool drawn_ = false;
  long last_done_ = -1;
  std::chrono::steady_clock::time_point start_, next_line_;
};

}  // namespace lagrange::tools
