#pragma once
/// @file
/// `lagrange sweep`, OUT/plan.json on disk, never held whole: a plan of 10
/// million rows is a file of a gigabyte or two. It is written line by line
/// (writePlanFile), and read without trusting it (PlanFile): opened once, not
/// through a link, a regular file of at most kMaxPlanBytes, hashed on the
/// way (SHA-256 of its bytes -- what a shard is given on its command line --
/// and of each 1 MiB piece), then read again piece by piece, each piece
/// checked against its hash of the first reading: every byte used is of the
/// file that was hashed, however the file is changed meanwhile.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tools/sweep/sweep_plan.hpp"
#include "util/input_file.hpp"

namespace lagrange::tools {

/// SHA-256, fed a piece at a time (OpenSSL's libcrypto).
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void add(const char* data, std::size_t size);
  std::array<std::uint8_t, 32> finish();  ///< the digest; the object is spent

 private:
  void* context_;  // EVP_MD_CTX
};

/// The digest as 64 lower-case hex digits.
std::string hexDigest(const std::array<std::uint8_t, 32>& digest);

/// Writes `plan` as plan.json to `path` (created anew, never through a link:
/// util/output_file.hpp), a line at a time; returns the SHA-256 of what it
/// wrote, in hex. @throws RuntimeFault, util::UnsafeOutputPath.
std::string writePlanFile(const SweepPlan& plan, const std::string& path);

/// A plan.json, opened and hashed. @throws config::ConfigError naming the
/// file when it is not a regular file, is a link or is larger than kMaxPlanBytes.
class PlanFile {
 public:
  explicit PlanFile(const std::string& path);
  const std::string& path() const { return path_; }
  /// SHA-256 of its bytes, in hex.
  const std::string& sha256() const { return sha256_; }
  /// Its size when it was hashed [bytes].
  long long size() const { return size_; }
  /// Its lines from the first, each without its newline, given to `on_line`
  /// (its number from 1 and its text) until it returns false; a last line
  /// without its newline is not given. Returns the bytes of the lines given,
  /// newlines included. @throws config::ConfigError when a
  /// piece differs from what was hashed (the file changed since it was
  /// opened) or a line is longer than kMaxSweepLineBytes.
  long long forEachLine(const std::function<bool(long, const std::string&)>& on_line) const;
  /// Its header (sweep_plan.hpp planHeaderFromJson): the plan, its rows counted.
  SweepPlan header() const;
  /// Its rows in order, each checked to be the row of its place, given to
  /// `on_row` until it returns false. @throws config::ConfigError when a row
  /// is not one, or the file ends before the header's count.
  void forEachRow(const SweepPlan& header, const std::function<bool(const SweepRow&)>& on_row) const;

 private:
  std::string path_, sha256_;
  util::InputFile file_;
  std::vector<std::array<std::uint8_t, 32>> pieces_;
  long long size_ = 0;
};

}  // namespace lagrange::tools
