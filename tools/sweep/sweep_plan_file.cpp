#include "tools/sweep/sweep_plan_file.hpp"

#include <openssl/evp.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <new>
#include <optional>

#include "config/scenario.hpp"
#include "tools/sweep/sweep_files.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace lagrange::tools {

namespace {

using config::ConfigError;

// The pieces a plan.json is hashed and checked in.
constexpr std::size_t kPieceBytes = 1 << 20;

EVP_MD_CTX* evp(void* context) { return static_cast<EVP_MD_CTX*>(context); }

std::array<std::uint8_t, 32> sha256Of(const char* data, std::size_t size) {
  Sha256 h;
  h.add(data, size);
  return h.finish();
}

// Reads up to `size` bytes at `offset`, as many as there are; -1 on an error.
ssize_t readAt(int fd, char* buf, std::size_t size, long long offset) {
  std::size_t got = 0;
  while (got < size) {
    const ssize_t n = pread(fd, buf + got, size - got, static_cast<off_t>(offset) + static_cast<off_t>(got));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return -1;
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  return static_cast<ssize_t>(got);
}

}  // namespace

Sha256::Sha256() : context_(EVP_MD_CTX_new()) {
  if (!context_ || EVP_DigestInit_ex(evp(context_), EVP_sha256(), nullptr) != 1) {
    EVP_MD_CTX_free(evp(context_));
    throw std::bad_alloc();  // OpenSSL fails only without memory
  }
}

Sha256::~Sha256() { EVP_MD_CTX_free(evp(context_)); }

void Sha256::add(const char* data, std::size_t size) {
  if (EVP_DigestUpdate(evp(context_), data, size) != 1) throw std::bad_alloc();
}

std::array<std::uint8_t, 32> Sha256::finish() {
  std::array<std::uint8_t, 32> out{};
  unsigned int written = 0;
  if (EVP_DigestFinal_ex(evp(context_), out.data(), &written) != 1 || written != out.size())
    throw std::bad_alloc();
  return out;
}

std::string hexDigest(const std::array<std::uint8_t, 32>& digest) {
  static const char* const kDigits = "0123456789abcdef";
  std::string hex;
  for (const std::uint8_t b : digest) {
    hex += kDigits[b >> 4];
    hex += kDigits[b & 15];
  }
  return hex;
}

std::string writePlanFile(const SweepPlan& plan, const std::string& path) {
  const int fd = util::createOutputFile(path);
  Sha256 hash;
  std::string buffer;
  const auto flush = [&] {
    hash.add(buffer.data(), buffer.size());
    util::writeAll(fd, buffer, path);
    buffer.clear();
  };
  try {
    forEachPlanLine(plan, [&](const std::string& line) {
      buffer += line;
      buffer += '\n';
      if (buffer.size() >= kPieceBytes) flush();
    });
    flush();
  } catch (...) {
    close(fd);
    throw;
  }
  if (close(fd) != 0) throw RuntimeFault(util::ioErrorText("writing", path, errno));
  return hexDigest(hash.finish());
}

PlanFile::PlanFile(const std::string& path) : path_(path) {
  const std::string expected = "the plan.json lagrange sweep wrote";
  file_ = util::InputFile::open(path, expected, util::Links::kRefuse);
  if (!file_.ok()) throw ConfigError(file_.error());
  if (file_.size() > kMaxPlanBytes)
    throw ConfigError("'" + path + "' holds " + std::to_string(file_.size()) + " bytes; expected " +
                      expected + " of at most " + std::to_string(kMaxPlanBytes) + " bytes");
  Sha256 whole;
  std::vector<char> piece(kPieceBytes);
  for (long long at = 0;; at += static_cast<long long>(kPieceBytes)) {
    const ssize_t got = readAt(file_.fd(), piece.data(), piece.size(), at);
    if (got < 0)
      throw ConfigError("cannot read '" + path + "' (" + std::strerror(errno) + "); expected " + expected);
    if (got == 0) break;
    if (at + got > kMaxPlanBytes)  // grown since it was opened: read no further
      throw ConfigError("'" + path + "' grew past " + std::to_string(kMaxPlanBytes) +
                        " bytes while it was read; expected " + expected + " of at most that");
    whole.add(piece.data(), static_cast<std::size_t>(got));
    size_ += got;
    pieces_.push_back(sha256Of(piece.data(), static_cast<std::size_t>(got)));
    if (static_cast<std::size_t>(got) < piece.size()) break;
  }
  sha256_ = hexDigest(whole.finish());
}

long long PlanFile::forEachLine(const std::function<bool(long, const std::string&)>& on_line) const {
  std::vector<char> piece(kPieceBytes);
  std::string line;
  long number = 1;
  long long given = 0;
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    const ssize_t got =
        readAt(file_.fd(), piece.data(), piece.size(), static_cast<long long>(k * kPieceBytes));
    if (got < 0 || sha256Of(piece.data(), static_cast<std::size_t>(got)) != pieces_[k])
      throw ConfigError("'" + path_ + "' changed while it was read (bytes " +
                        std::to_string(k * kPieceBytes) +
                        " on differ from what was hashed when it was opened); expected the plan.json of the "
                        "sweep, left as it was written");
    for (ssize_t i = 0; i < got; ++i) {
      if (piece[static_cast<std::size_t>(i)] != '\n') {
        if (line.size() >= kMaxSweepLineBytes)
          throw ConfigError("'" + path_ + "' line " + std::to_string(number) + " is longer than " +
                            std::to_string(kMaxSweepLineBytes) +
                            " bytes; expected the plan.json lagrange sweep wrote");
        line.push_back(piece[static_cast<std::size_t>(i)]);
        continue;
      }
      given += static_cast<long long>(line.size()) + 1;
      if (!on_line(number++, line)) return given;
      line.clear();
    }
  }
  return given;
}

SweepPlan PlanFile::header() const {
  std::optional<SweepPlan> plan;
  forEachLine([&](long, const std::string& line) {
    plan = planHeaderFromJson(line, path_);
    return false;
  });
  if (!plan) throw ConfigError(path_ + ": not a sweep plan written by lagrange sweep (no header line)");
  return std::move(*plan);
}

void PlanFile::forEachRow(const SweepPlan& header, const std::function<bool(const SweepRow&)>& on_row) const {
  const long rows = static_cast<long>(header.rows.size());
  long next = 0;
  bool stopped = false;
  forEachLine([&](long number, const std::string& line) {
    if (number == 1) return true;  // the header
    if (next >= rows) return false;
    const SweepRow row = planRowFromJson(line, next++, path_);
    stopped = !on_row(row);
    return !stopped;
  });
  if (!stopped && next < rows)
    throw ConfigError(path_ +
                      ": not a sweep plan written by lagrange sweep (fewer rows than its header says)");
}

}  // namespace lagrange::tools
