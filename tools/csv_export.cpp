#include "tools/csv_export.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <set>
#include <stdexcept>
#include <vector>

#include "lagrange/actuator_state_t.hpp"
#include "lagrange/control_command_t.hpp"
#include "lagrange/plant_motor_t.hpp"
#include "lagrange/plant_position_t.hpp"
#include "lagrange/plant_truth_t.hpp"
#include "transport/channels.hpp"

namespace lagrange::tools {

namespace {

// One CSV row under construction: named columns in order.
class Row {
 public:
  void add(const std::string& name, double value) {
    names_.push_back(name);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", value);
    values_.push_back(buf);
  }
  void add(const std::string& name, const std::vector<double>& values) {
    for (size_t i = 0; i < values.size(); ++i) add(name + "[" + std::to_string(i) + "]", values[i]);
  }
  void add(const std::string& name, const std::vector<std::vector<double>>& rows) {
    for (size_t i = 0; i < rows.size(); ++i) add(name + "[" + std::to_string(i) + "]", rows[i]);
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

template <class Msg>
bool decode(const lcm::LogEvent& ev, Msg& m) {
  try {
    return m.decode(ev.data, 0, static_cast<int>(ev.datalen)) == static_cast<int>(ev.datalen);
  } catch (const std::exception&) {
    return false;
  }
}

void headerColumns(Row& row, const lagrange::header_t& h) {
  row.add("tick", static_cast<double>(h.tick));
  row.add("sim_time", h.sim_time);
}

// The row of one event of a known channel; false if the event is not decodable.
bool rowOf(const lcm::LogEvent& ev, Row& row, int64_t& tick) {
  const std::string& ch = ev.channel;
  if (ch == transport::kPlantTruth) {
    lagrange::plant_truth_t m;
    if (!decode(ev, m)) return false;
    headerColumns(row, m.header);
    row.add("q", m.q), row.add("qdot", m.qdot), row.add("tau_applied", m.tau_applied);
    row.add("kinetic_energy", m.kinetic_energy), row.add("potential_energy", m.potential_energy);
    row.add("total_energy", m.total_energy);
    tick = m.header.tick;
  } else if (ch == transport::kPlantPosition) {
    lagrange::plant_position_t m;
    if (!decode(ev, m)) return false;
    headerColumns(row, m.header);
    row.add("q", m.q);
    tick = m.header.tick;
  } else if (ch == transport::kPlantMotor) {
    lagrange::plant_motor_t m;
    if (!decode(ev, m)) return false;
    headerColumns(row, m.header);
    row.add("q", m.q), row.add("qdot", m.qdot);
    tick = m.header.tick;
  } else if (ch == transport::kControlCommand) {
    lagrange::control_command_t m;
    if (!decode(ev, m)) return false;
    headerColumns(row, m.header);
    row.add("u", m.u), row.add("q_desired", m.q_desired), row.add("q_error", m.q_error);
    row.add("theta", m.theta), row.add("filter_state", m.filter_state), row.add("xi_error", m.xi_error);
    tick = m.header.tick;
  } else if (ch == transport::kActuatorState) {
    lagrange::actuator_state_t m;
    if (!decode(ev, m)) return false;
    headerColumns(row, m.header);
    row.add("u_commanded", m.u_commanded), row.add("tau_applied", m.tau_applied), row.add("xi", m.xi);
    tick = m.header.tick;
  } else {
    return false;
  }
  return true;
}

}  // namespace

std::map<std::string, long long> exportCsv(const std::string& log_path, const std::string& out_dir) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) throw std::runtime_error("cannot open " + log_path + " as an LCM log");
  std::filesystem::create_directories(out_dir);
  std::map<std::string, std::ofstream> files;
  std::map<std::string, std::set<int64_t>> seen;
  std::map<std::string, long long> rows;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    Row row;
    int64_t tick = 0;
    if (!rowOf(*ev, row, tick) || !seen[ev->channel].insert(tick).second) continue;
    auto [it, fresh] = files.try_emplace(ev->channel);
    if (fresh) {
      it->second.open(std::filesystem::path(out_dir) / (ev->channel + ".csv"));
      if (!it->second) throw std::runtime_error("cannot write " + out_dir + "/" + ev->channel + ".csv");
      it->second << row.header() << "\n";
    }
    it->second << row.line() << "\n";
    ++rows[ev->channel];
  }
  for (auto& [channel, file] : files)
    if (!file.flush()) throw std::runtime_error("writing " + out_dir + "/" + channel + ".csv failed");
  return rows;
}

}  // namespace lagrange::tools
