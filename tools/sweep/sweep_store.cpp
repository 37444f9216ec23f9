#include "tools/sweep/sweep_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "tools/sweep/sweep_files.hpp"
#include "tools/sweep/sweep_runner.hpp"
#include "tools/sweep/sweep_values.hpp"
#include "util/error.hpp"
#include "util/input_file.hpp"
#include "util/output_file.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;

// Each file written beside its name (never through a link planted there),
// then all renamed over theirs: none is left half-written, and none is
// replaced unless every one was written.
void writeAtomically(const std::vector<std::pair<fs::path, std::string>>& files) {
  for (const auto& [path, text] : files) util::writeOutputFile(path.string() + ".tmp", text);
  for (const auto& [path, text] : files) fs::rename(path.string() + ".tmp", path);
}

}  // namespace

namespace {

// Refusals named in full; the rest are counted.
constexpr std::size_t kRefusalsNamed = 10;

// The shard a rows file's name says wrote it: rows/shard-K-of-N.jsonl, with
// 0 <= K < N <= the plan's rows (there are never more shards than rows).
struct ShardOfFile {
  long k = 0, n = 0;
};
std::optional<ShardOfFile> shardOf(const std::string& file_name, long plan_rows) {
  static const std::regex pattern(R"(shard-([0-9]{1,9})-of-([0-9]{1,9})\.jsonl)");
  std::smatch m;
  if (!std::regex_match(file_name, m, pattern)) return std::nullopt;
  const ShardOfFile s{std::stol(m[1]), std::stol(m[2])};
  if (s.n < 1 || s.k >= s.n || s.n > std::max(1L, plan_rows)) return std::nullopt;
  return s;
}

// Why a parsed line is not a row of the plan that shard `shard` may have written, or "".
std::string rowProblem(const nlohmann::ordered_json& j, long plan_rows, const ShardOfFile& shard) {
  const std::string expected = "; expected a whole number from 0 to " + std::to_string(plan_rows - 1) +
                               " (the plan has " + std::to_string(plan_rows) + " rows)";
  if (!j.is_object())
    return "a JSON " + std::string(j.type_name()) + ", not a row; expected an object with an index";
  const auto index = j.find("index");
  if (index == j.end()) return "no index; expected a row with its index";
  if (!index->is_number_integer()) return "index " + index->dump() + " is not a whole number" + expected;
  const bool inside = index->is_number_unsigned()
                          ? index->get<std::uint64_t>() < static_cast<std::uint64_t>(plan_rows)
                          : index->get<std::int64_t>() >= 0 && index->get<std::int64_t>() < plan_rows;
  if (!inside) return "index " + index->dump() + " is outside the plan" + expected;
  if (const long i = static_cast<long>(index->get<std::int64_t>()); i % shard.n != shard.k)
    return "index " + std::to_string(i) + " is not a row of shard " + std::to_string(shard.k) + " of " +
           std::to_string(shard.n) + "; expected an index whose remainder by " + std::to_string(shard.n) +
           " is " + std::to_string(shard.k);
  return "";
}

// A row written before the simulated verdict existed: its sampled_verdict
// was the linearised one (now linearised_verdict).
void upgradeOldRow(nlohmann::ordered_json& row) {
  if (!row.contains("linearised_verdict") && row.contains("sampled_verdict")) {
    row["linearised_verdict"] = row["sampled_verdict"];
    row["sampled_verdict"] = nullptr;
  }
}

}  // namespace

namespace {
// The line of `file` where row `index` was first taken (as readFinishedRows
// takes a row: the first line with that index that passes), for a message.
long firstLineWith(const fs::path& file, long index, long plan_rows, const ShardOfFile& shard,
                   long long max_file_bytes) {
  long found = 0;
  forEachLine(file.string(), "a rows file of lagrange sweep", max_file_bytes, [&](const FileLine& line) {
    std::string why;
    const std::optional<nlohmann::ordered_json> j = parseSweepJson(line.text, why);
    if (!line.too_long && j && rowProblem(*j, plan_rows, shard).empty() &&
        j->at("index").get<std::int64_t>() == index)
      found = line.number;
    return found == 0;
  });
  return found;
}
}  // namespace

FinishedRows readFinishedRows(const std::string& out_dir, long plan_rows, bool keep_rows,
                              const std::vector<std::string>& param_columns) {
  FinishedRows out;
  out.done.assign(static_cast<size_t>(std::max(0L, plan_rows)), false);
  const auto refuse = [&out](const std::string& why) {
    if (out.refusals.size() < kRefusalsNamed) out.refusals.push_back(why);
    ++out.refused;
  };
  const fs::path dir = fs::path(out_dir) / "rows";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".jsonl") files.push_back(e.path());
  std::sort(files.begin(), files.end());  // the same row from the same file every time
  // The sweep's own files belong to whoever planned it; in a shared folder
  // a file of another user is not one of them.
  std::optional<uid_t> owner;
  if (struct stat plan{}; lstat((fs::path(out_dir) / "plan.json").c_str(), &plan) == 0) owner = plan.st_uid;
  // Per row, the file (its place in `files`, from 1) it was first taken from
  // (made at the first row taken); its line is looked for again only when a
  // repeat is named.
  std::vector<std::uint32_t> first_file;
  std::vector<ShardOfFile> shards(files.size());
  // Every row once, each at most a line's bound, and a partial last line.
  const long long max_file_bytes =
      (static_cast<long long>(plan_rows) + 1) * static_cast<long long>(kMaxSweepLineBytes);
  for (size_t file_number = 0; file_number < files.size(); ++file_number) {
    const fs::path& f = files[file_number];
    const std::string name = f.string();
    const std::optional<ShardOfFile> shard = shardOf(f.filename().string(), plan_rows);
    if (!shard) {
      refuse("'" + name +
             "' is not named as a shard of this sweep writes its rows; expected shard-K-of-N.jsonl with " +
             "0 <= K < N <= " + std::to_string(plan_rows) + "; its rows were not read");
      continue;
    }
    shards[file_number] = *shard;
    const std::string error = forEachLine(
        name, "a rows file of lagrange sweep", max_file_bytes,
        [&](const FileLine& line) {
          const std::string at = name + " line " + std::to_string(line.number) + ": ";
          if (line.too_long) {
            refuse(at + "longer than " + std::to_string(kMaxSweepLineBytes) +
                   " bytes; expected one row of a few hundred");
            return true;
          }
          std::string why;
          std::optional<nlohmann::ordered_json> j = parseSweepJson(line.text, why);
          if (j && (why = rowProblem(*j, plan_rows, *shard)).empty()) {
            const long index = static_cast<long>(j->at("index").get<std::int64_t>());
            const auto i = static_cast<size_t>(index);
            if (!out.done[i]) {
              if (first_file.empty()) first_file.assign(out.done.size(), 0);
              out.done[i] = true;
              first_file[i] = static_cast<std::uint32_t>(file_number + 1);
              ++out.count;
              if (keep_rows) {
                upgradeOldRow(*j);
                typeOldParams(*j, param_columns);
                out.rows.emplace(index, std::move(*j));
              }
              return true;
            }
            const size_t first = first_file[i] - 1;
            why = "row " + std::to_string(index) + " again (first in " + files[first].string();
            if (out.refusals.size() < kRefusalsNamed)  // named: its first line looked for
              why += " line " + std::to_string(firstLineWith(files[first], index, plan_rows, shards[first],
                                                             max_file_bytes));
            why += "); expected each row once";
          }
          refuse(at + why);
          return true;
        },
        owner);
    if (!error.empty()) refuse(error + "; its rows were not read");
  }
  return out;
}

RowWriter::RowWriter(const std::string& path) : path_(path) {
  // Never through a link: a planted rows/shard-K-of-N.jsonl -> ~/.bashrc would have it cut and appended to.
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  if (fd_ < 0 && errno == ELOOP)
    throw util::UnsafeOutputPath(
        "'" + path +
        "' is a symbolic link; expected a rows file of lagrange sweep or nothing there "
        "(rows are never written through a link)");
  if (fd_ < 0) throw RuntimeFault("cannot open " + path + ": " + std::strerror(errno));
  struct stat st {};
  if (fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw util::UnsafeOutputPath(
        "'" + path + "' is " + util::fileKindText(st.st_mode) +
        "; expected a rows file of lagrange sweep (a regular file) or nothing there");
  }
  // Cut a partial last line (a writer killed mid-write) back to the last newline.
  const off_t size = ::lseek(fd_, 0, SEEK_END);
  off_t keep = size;
  char c = '\n';
  while (keep > 0 && ::pread(fd_, &c, 1, keep - 1) == 1 && c != '\n') --keep;
  if (keep != size && ::ftruncate(fd_, keep) != 0)
    throw RuntimeFault("cannot truncate " + path + ": " + std::strerror(errno));
}

RowWriter::~RowWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void RowWriter::append(const nlohmann::ordered_json& row) {
  const std::string line = row.dump() + "\n";
  // O_APPEND and one write: the line lands whole or (killed mid-call) as a
  // tail without its newline, which readers drop.
  const ssize_t n = ::write(fd_, line.data(), line.size());
  if (n != static_cast<ssize_t>(line.size()))
    throw RuntimeFault("cannot append to " + path_ + ": " + (n < 0 ? std::strerror(errno) : "short write"));
}

void writeSweepTable(const std::string& out_dir, const SweepPlan& plan,
                     const std::map<long, nlohmann::ordered_json>& rows) {
  // A vector axis is a column per element in the CSV (sweep_values.hpp).
  std::vector<CsvParamColumn> columns = {{"index", "index", -1}};
  for (CsvParamColumn& c : csvParamColumns(plan.param_columns, rows)) columns.push_back(std::move(c));
  for (const std::string& c : resultColumns()) columns.push_back({c, c, -1});
  std::ostringstream csv, jsonl;
  for (size_t i = 0; i < columns.size(); ++i) csv << (i ? "," : "") << columns[i].name;
  csv << "\n";
  for (const auto& [index, row] : rows) {
    for (size_t i = 0; i < columns.size(); ++i) {
      const auto v = row.find(columns[i].column);
      csv << (i ? "," : "");
      if (v == row.end()) continue;
      if (columns[i].element < 0)
        csv << csvField(*v);
      else if (v->is_array())  // a row without a value (null) has none of its elements either
        csv << csvField(v->at(static_cast<size_t>(columns[i].element)));
    }
    csv << "\n";
    jsonl << row.dump() << "\n";
  }
  writeAtomically(
      {{fs::path(out_dir) / "sweep.csv", csv.str()}, {fs::path(out_dir) / "sweep.jsonl", jsonl.str()}});
}

}  // namespace lagrange::tools
