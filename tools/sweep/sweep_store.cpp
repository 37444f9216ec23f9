#include "tools/sweep/sweep_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "tools/sweep/sweep_runner.hpp"
#include "util/error.hpp"
#include "util/number_text.hpp"
#include "util/output_file.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;

std::string csvField(const nlohmann::ordered_json& v) {
  std::string text;
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_float()) return util::exactText(v.get<double>());
  text = v.is_string() ? v.get<std::string>() : v.dump();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return quoted + "\"";
}

void writeAtomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  util::writeOutputFile(tmp.string(), text);  // never through a link planted at tmp
  fs::rename(tmp, path);
}

}  // namespace

std::map<long, nlohmann::ordered_json> readFinishedRows(const std::string& out_dir) {
  std::map<long, nlohmann::ordered_json> rows;
  const fs::path dir = fs::path(out_dir) / "rows";
  if (!fs::is_directory(dir)) return rows;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".jsonl") files.push_back(e.path());
  std::sort(files.begin(), files.end());  // the same row from the same file every time
  for (const fs::path& f : files) {
    std::ifstream in(f, std::ios::binary);
    std::string line;
    while (std::getline(in, line)) {
      if (in.eof()) break;  // no newline: a line a killed shard did not finish
      nlohmann::ordered_json j = nlohmann::ordered_json::parse(line, nullptr, false);
      if (j.is_discarded() || !j.contains("index")) continue;
      // A row written before the simulated verdict existed: its
      // sampled_verdict was the linearised one (now linearised_verdict).
      if (!j.contains("linearised_verdict") && j.contains("sampled_verdict")) {
        j["linearised_verdict"] = j["sampled_verdict"];
        j["sampled_verdict"] = nullptr;
      }
      rows.emplace(j["index"].get<long>(), std::move(j));
    }
  }
  return rows;
}

RowWriter::RowWriter(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RuntimeFault("cannot open " + path + ": " + std::strerror(errno));
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

std::vector<std::string> tableColumns(const SweepPlan& plan) {
  std::vector<std::string> columns = {"index"};
  columns.insert(columns.end(), plan.param_columns.begin(), plan.param_columns.end());
  for (const std::string& c : resultColumns()) columns.push_back(c);
  return columns;
}

void writeSweepTable(const std::string& out_dir, const SweepPlan& plan,
                     const std::map<long, nlohmann::ordered_json>& rows) {
  const std::vector<std::string> columns = tableColumns(plan);
  std::ostringstream csv, jsonl;
  for (size_t i = 0; i < columns.size(); ++i) csv << (i ? "," : "") << columns[i];
  csv << "\n";
  for (const auto& [index, row] : rows) {
    for (size_t i = 0; i < columns.size(); ++i)
      csv << (i ? "," : "") << (row.contains(columns[i]) ? csvField(row.at(columns[i])) : "");
    csv << "\n";
    jsonl << row.dump() << "\n";
  }
  writeAtomically(fs::path(out_dir) / "sweep.csv", csv.str());
  writeAtomically(fs::path(out_dir) / "sweep.jsonl", jsonl.str());
}

}  // namespace lagrange::tools
