#include "tools/sweep/sweep_progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "tools/sweep/sweep_files.hpp"
#include "util/input_file.hpp"

namespace lagrange::tools {

namespace {

std::string duration(double s) {
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%.0fs", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  else
    std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s) / 3600, static_cast<int>(s) % 3600 / 60);
  return buf;
}

}  // namespace

RowCount RowCounter::count() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(dir_) / "rows";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() != ".jsonl") continue;
    // As the table reads them (sweep_files.hpp): a link, a FIFO or a device
    // is not counted, and never blocks or fills the progress loop.
    const util::InputFile file =
        util::InputFile::open(e.path().string(), "a rows file of lagrange sweep", util::Links::kRefuse);
    if (!file.ok()) continue;
    long long& offset = offsets_[e.path().string()];
    // Whole lines only, read from where the last count stopped: a line
    // still being written is read next time; an over-long one only counted.
    std::string line;
    char buf[65536];
    for (long long at = offset; at < file.size();) {
      const ssize_t got = pread(
          file.fd(), buf, static_cast<std::size_t>(std::min<long long>(sizeof buf, file.size() - at)), at);
      if (got <= 0) break;
      for (ssize_t i = 0; i < got; ++i) {
        if (buf[i] != '\n') {
          if (line.size() < kMaxSweepLineBytes) line.push_back(buf[i]);
          continue;
        }
        offset = at + i + 1;
        ++total_.rows;
        if (line.find("\"diverged\":true") != std::string::npos) ++total_.diverged;
        line.clear();
      }
      at += got;
    }
  }
  return total_;
}

SweepProgress::SweepProgress(long total, long done_at_start, bool quiet)
    : total_(total),
      start_done_(done_at_start),
      quiet_(quiet),
      tty_(isatty(STDOUT_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      next_line_(start_) {}

void SweepProgress::update(long done, long diverged) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  if (tty_ ? done == last_done_ && now < next_line_ : now < next_line_) return;
  next_line_ = now + std::chrono::seconds(tty_ ? 1 : 10);
  last_done_ = done;
  draw(done, diverged);
}

void SweepProgress::draw(long done, long diverged) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const long new_rows = done - start_done_;
  const double rate = elapsed > 0 ? static_cast<double>(new_rows) / elapsed : 0.0;
  const std::string eta = rate > 0 ? duration(static_cast<double>(total_ - done) / rate) : std::string("?");
  const double fraction = total_ > 0 ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  char text[160];
  std::snprintf(text, sizeof text, "%ld/%ld runs (%.0f%%), %.2f runs/s, ETA %s, %ld diverged", done, total_,
                100 * fraction, rate, eta.c_str(), diverged);
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::printf("\r[%s%s] %s\x1b[K", std::string(static_cast<size_t>(filled), '#').c_str(),
                std::string(static_cast<size_t>(kWidth - filled), ' ').c_str(), text);
    drawn_ = true;
  } else {
    std::printf("progress: %s\n", text);
  }
  std::fflush(stdout);
}

void SweepProgress::interrupt() {
  if (drawn_) std::printf("\n");
  drawn_ = false;
  std::fflush(stdout);
}

void SweepProgress::finish(long done, long diverged) {
  if (!quiet_ && done != last_done_) draw(done, diverged);
  interrupt();
}

}  // namespace lagrange::tools
