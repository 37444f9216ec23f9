#pragma once
/// @file
/// Reading what is in a sweep's output directory without trusting it. The
/// directory may be shared (a Slurm job's folder on NFS, writable by others),
/// so its files may be planted: a rows file linked to /dev/zero or a FIFO, a
/// line of a gigabyte, a row nested 200 000 deep (nlohmann parses it, but
/// writing it out again recurses once per level: SIGSEGV). Each file is
/// opened without following links and refused unless it is a regular file
/// of a bounded size (util/input_file.hpp); each line is read up to a bound
/// and parsed with its nesting bounded before a value is built.

#include <sys/types.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace lagrange::tools {

/// A line of a rows file or of plan.json: a finished row is about 600 bytes,
/// a plan's row its overrides; 64 KiB is far beyond either.
inline constexpr std::size_t kMaxSweepLineBytes = 64 << 10;
/// Nesting of a row or a plan line: objects of lists (an axis value may be a
/// YAML list or map, a few levels deep).
inline constexpr int kMaxSweepJsonDepth = 32;
/// plan.json: 10 million rows (the most a sweep may have) of 1.6 KiB (a row
/// of a 7-joint arm's initial state and filter state with its `set` is about
/// 400 bytes). It is never held whole (sweep_plan_file.hpp), so the bound is
/// on the time a shard spends reading it, not on memory.
inline constexpr long long kMaxPlanBytes = 16LL << 30;

/// `text` parsed as JSON, refusing nesting deeper than kMaxSweepJsonDepth as
/// soon as the parser meets it. On failure nothing, and `error` says why.
std::optional<nlohmann::ordered_json> parseSweepJson(const std::string& text, std::string& error);

/// The whole regular file at `path` -- not a link, at most `max_bytes` -- or
/// nothing, with `error` saying why (the file, what it is, what was expected).
std::optional<std::string> readSweepFile(const std::string& path, const std::string& expected,
                                         long long max_bytes, std::string& error);

/// One line of a file read by forEachLine: its number (from 1) and text; an
/// over-long line has `too_long` set and its text cut at the bound.
struct FileLine {
  long number = 0;
  std::string text;
  bool too_long = false;
};

/// Calls on_line for each whole line (ended by a newline) of the regular file
/// at `path` -- not a link, at most `max_file_bytes`, owned by `owner` when
/// one is given -- holding at most
/// kMaxSweepLineBytes of each line in memory; a last line without its
/// newline (a writer killed mid-line) is not passed. `expected` names the
/// file in errors. On_line returns false to stop. Returns "" or why the file
/// was not read ("'P' is a FIFO (named pipe); expected ...", "... is larger
/// than ...").
std::string forEachLine(const std::string& path, const std::string& expected, long long max_file_bytes,
                        const std::function<bool(const FileLine&)>& on_line,
                        std::optional<uid_t> owner = std::nullopt);

}  // namespace lagrange::tools
