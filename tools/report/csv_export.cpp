#include "tools/report/csv_export.hpp"

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_rate_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "logs/log_reader.hpp"
#include "transport/channels.hpp"
#include "transport/message_fields.hpp"
#include "util/number_text.hpp"
#include "util/output_stream.hpp"

namespace lagrange::tools {

namespace {

// One CSV row under construction: named columns in order (a visitor of
// transport::fields; the units are the docs', not the columns').
class Row {
 public:
  void add(const std::string& name, double value, const char* /*unit*/ = "") {
    names_.push_back(name);
    values_.push_back(util::exactText(value));
  }
  // Joints (and torque steps, chain stages) numbered from 1, as the plots,
  // the URDF's joint names and the paper number them: q[1] is joint 1.
  void add(const std::string& name, const std::vector<double>& values, const char* unit = "") {
    for (size_t i = 0; i < values.size(); ++i) add(name + "[" + std::to_string(i + 1) + "]", values[i], unit);
  }
  void add(const std::string& name, const std::vector<std::vector<double>>& rows, const char* unit = "") {
    for (size_t i = 0; i < rows.size(); ++i) add(name + "[" + std::to_string(i + 1) + "]", rows[i], unit);
  }
  std::string header() const { return join(names_); }
  std::string line() const { return join(values_); }

 private:
  static std::string join(const std::vector<std::string>& parts) {
    std::string out;
    for (size_t i = 0; i < parts.size(); ++i) out += (i ? "," : "") + parts[i];
    return out;
  }
  std::vector<std::string> names_, values_;
};

void headerColumns(Row& row, const lagrange::header_t& h) {
  row.add("tick", static_cast<double>(h.tick));
  row.add("sim_time", h.sim_time);
}

// The row of one event of a known channel; false if the event is not decodable.
bool rowOf(const lcm::LogEvent& ev, Row& row, int64_t& tick) {
  return transport::withChannelMessage(ev.channel, false, [&](auto m) {
    if (!logs::decodeEvent(ev, m)) return false;
    headerColumns(row, m.header);
    transport::fields(row, m);
    tick = m.header.tick;
    return true;
  });
}

// Wall-clock publish times by tick, for the timing of a realtime run.
struct PublishTimes {
  std::map<int64_t, int64_t> position, command, actuator;
};

// The ticks a publish time is filed under: a command's is the position it answers.
void notePublishTime(const lagrange::plant_position_t& m, PublishTimes& times) {
  times.position.emplace(m.header.tick, m.header.publish_utime);
}
void notePublishTime(const lagrange::control_command_t& m, PublishTimes& times) {
  times.command.emplace(m.input_position_tick, m.header.publish_utime);
}
void notePublishTime(const lagrange::actuator_state_t& m, PublishTimes& times) {
  times.actuator.emplace(m.header.tick, m.header.publish_utime);
}
template <class Other>
void notePublishTime(const Other&, PublishTimes&) {}  // not part of the timing

void notePublishTime(const lcm::LogEvent& ev, PublishTimes& times) {
  transport::withChannelMessage(ev.channel, false, [&](auto m) {
    if (logs::decodeEvent(ev, m)) notePublishTime(m, times);
    return true;
  });
}

// TIMING.csv: per tick, the plant's period error and the latencies from its
// sample to the command and to the actuator state answering it [us].
long long writeTiming(const PublishTimes& times, double period, const std::string& path) {
  util::OutputStream out(path);
  out << "tick,period_error_us,command_latency_us,actuator_latency_us\n";
  long long rows = 0;
  const auto after = [&](const std::map<int64_t, int64_t>& m, int64_t tick, int64_t published) {
    const auto it = m.find(tick);
    return it == m.end() ? std::string() : std::to_string(it->second - published);
  };
  std::optional<std::pair<int64_t, int64_t>> previous;
  for (const auto& [tick, published] : times.position) {
    std::string period_error;
    if (previous && previous->first == tick - 1)
      period_error = std::to_string(static_cast<double>(published - previous->second) - period * 1e6);
    out << tick << "," << period_error << "," << after(times.command, tick, published) << ","
        << after(times.actuator, tick, published) << "\n";
    previous = {tick, published};
    ++rows;
  }
  out.close();
  return rows;
}

// One channel's CSV file, rows in tick order: a lockstep tick the logger
// lacked and the plant re-sent is in the log a few ticks late (at most
// lockstep.logger_window). Rows wait in a window of kHeldTicks ticks, so the
// memory stays bounded however long the run.
class TickOrderedCsv {
 public:
  static constexpr int64_t kHeldTicks = 1000;

  explicit TickOrderedCsv(const std::filesystem::path& path) : out_(path.string()) {}
  void header(const std::string& line) { out_ << line << "\n"; }
  void add(int64_t tick, std::string line) {
    held_.emplace(tick, std::move(line));
    while (!held_.empty() && held_.begin()->first < held_.rbegin()->first - kHeldTicks) writeFirst();
  }
  void finish() {
    while (!held_.empty()) writeFirst();
    out_.close();
  }

 private:
  void writeFirst() {
    out_ << held_.begin()->second << "\n";
    held_.erase(held_.begin());
  }
  util::OutputStream out_;
  std::map<int64_t, std::string> held_;
};

}  // namespace

CsvExport exportCsv(const std::string& log_path, const std::string& out_dir) {
  util::makeOutputDirectories(out_dir);
  CsvExport result;
  std::map<std::string, TickOrderedCsv> files;
  std::map<std::string, std::set<int64_t>> seen;
  result.scan = logs::readLog(log_path, [&](const lcm::LogEvent& ev) {
    if (ev.channel == transport::kScenario && !result.scenario) result.scenario = logs::scenarioYaml(ev);
    Row row;
    int64_t tick = 0;
    if (!rowOf(ev, row, tick) || !seen[ev.channel].insert(tick).second) return;
    auto it = files.find(ev.channel);
    if (it == files.end()) {
      it = files.try_emplace(ev.channel, std::filesystem::path(out_dir) / (ev.channel + ".csv")).first;
      it->second.header(row.header());
    }
    it->second.add(tick, row.line());
    ++result.rows[ev.channel];
  });
  for (auto& [channel, file] : files) file.finish();
  return result;
}

long long exportTiming(const std::string& log_path, double period, const std::string& out_dir) {
  PublishTimes times;
  logs::readLog(log_path, [&](const lcm::LogEvent& ev) { notePublishTime(ev, times); });
  if (times.position.empty()) return 0;
  return writeTiming(times, period,
                     (std::filesystem::path(out_dir) / (std::string(kTimingChannel) + ".csv")).string());
}

}  // namespace lagrange::tools
