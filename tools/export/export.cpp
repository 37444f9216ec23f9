#include "tools/export/export.hpp"

#include <H5Cpp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <type_traits>

#include "config/input_file.hpp"
#include "config/scenario.hpp"
#include "logs/event_bounds.hpp"
#include "tools/export/hdf5_write.hpp"
#include "tools/export/tracking_export.hpp"
#include "transport/channels.hpp"
#include "transport/message_fields.hpp"
#include "util/error.hpp"
#include "util/input_file.hpp"
#include "util/output_file.hpp"

namespace lagrange::tools {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFormat = "lagrange run export 1";
// Rows held before they are written, so that they go out in runs of
// contiguous rows (one write per dataset each), not one write a row.
constexpr size_t kHeldRows = 4096;
constexpr size_t kHeldValues = size_t{1} << 22;  // 32 MiB of doubles across the channels

// A field's shape from the first message: [] a number, [joints], or [rows, joints].
struct FieldShape {
  std::string name, unit;
  std::vector<hsize_t> dims;
  size_t size() const {
    size_t n = 1;
    for (hsize_t d : dims) n *= d;
    return n;
  }
};

struct ShapeVisitor {
  std::vector<FieldShape> fields;
  void add(const std::string& name, double, const char* unit) { fields.push_back({name, unit, {}}); }
  void add(const std::string& name, const std::vector<double>& v, const char* unit) {
    fields.push_back({name, unit, {v.size()}});
  }
  void add(const std::string& name, const std::vector<std::vector<double>>& rows, const char* unit) {
    fields.push_back({name, unit, {rows.size(), rows.empty() ? 0 : rows.front().size()}});
  }
};

// One message's values, flat in the fields' order; a value of another shape
// than the first message's is NaN-filled (and counted).
struct FlatVisitor {
  const std::vector<FieldShape>& shapes;
  std::vector<double> values;
  size_t field = 0;
  bool misshapen = false;
  void put(const std::vector<double>& flat) {
    const size_t want = shapes.at(field++).size();
    if (flat.size() != want) misshapen = true;
    for (size_t i = 0; i < want; ++i)
      values.push_back(i < flat.size() && flat.size() == want ? flat[i] : std::nan(""));
  }
  void add(const std::string&, double v, const char*) { put({v}); }
  void add(const std::string&, const std::vector<double>& v, const char*) { put(v); }
  void add(const std::string&, const std::vector<std::vector<double>>& rows, const char*) {
    std::vector<double> flat;
    const size_t width = shapes.at(field).dims.size() == 2 ? shapes.at(field).dims[1] : 0;
    for (const auto& r : rows) {
      if (r.size() != width) misshapen = true;
      flat.insert(flat.end(), r.begin(), r.end());
    }
    put(flat);
  }
};

struct Row {
  int64_t tick = 0, utime = 0;
  double t = 0.0;
  std::vector<double> values;
};

// One channel's group: its ticks (pass 1), its datasets and held rows (pass 2).
struct ChannelTable {
  std::vector<FieldShape> fields;
  std::vector<int64_t> ticks;  // sorted, unique
  std::vector<bool> written;
  std::map<size_t, Row> held;
  H5::Group group;
  H5::DataSet tick, t, utime;
  std::vector<H5::DataSet> datasets;  // per field; an empty field has none
  long long misshapen = 0;
};

// Decodes `ev` as its channel's type and calls f(message); false if it is
// not a whole, intact message of a per-tick channel.
template <class F>
bool withMessage(const lcm::LogEvent& ev, F&& f) {
  return transport::withChannelMessage(ev.channel, false, [&](auto m) {
    if (!logs::decodeEvent(ev, m)) return false;
    f(m);
    return true;
  });
}

using hdf5::dataset;
using hdf5::textAttribute;
using hdf5::textListAttribute;
using hdf5::writeRows;

// Writes the held rows of a table, each contiguous run in one write per dataset.
void flush(ChannelTable& c) {
  while (!c.held.empty()) {
    const size_t first = c.held.begin()->first;
    size_t count = 0;
    for (auto it = c.held.begin(); it != c.held.end() && it->first == first + count; ++it) ++count;
    std::vector<int64_t> ticks, utimes;
    std::vector<double> times;
    std::vector<std::vector<double>> columns(c.fields.size());
    auto it = c.held.begin();
    for (size_t k = 0; k < count; ++k, ++it) {
      ticks.push_back(it->second.tick), utimes.push_back(it->second.utime), times.push_back(it->second.t);
      size_t offset = 0;
      for (size_t f = 0; f < c.fields.size(); ++f) {
        const size_t n = c.fields[f].size();
        columns[f].insert(columns[f].end(), it->second.values.begin() + static_cast<long>(offset),
                          it->second.values.begin() + static_cast<long>(offset + n));
        offset += n;
      }
    }
    writeRows(c.tick, H5::PredType::NATIVE_INT64, ticks.data(), first, count);
    writeRows(c.utime, H5::PredType::NATIVE_INT64, utimes.data(), first, count);
    writeRows(c.t, H5::PredType::NATIVE_DOUBLE, times.data(), first, count);
    for (size_t f = 0; f < c.fields.size(); ++f)
      if (c.fields[f].size() > 0)
        writeRows(c.datasets[f], H5::PredType::NATIVE_DOUBLE, columns[f].data(), first, count);
    c.held.erase(c.held.begin(), it);
  }
}

// summary.json: a few kB of metrics; 16 MiB is far beyond any run's.
constexpr std::uintmax_t kMaxSummaryBytes = 16u << 20;

// A file next to the log, when there is one: read only if it is a regular
// file of at most max_bytes (a FIFO there would block the export, /dev/zero
// fill its memory), else left out with a warning naming it.
std::optional<std::string> runFileText(const fs::path& p, std::uintmax_t max_bytes,
                                       const std::string& expected, std::vector<std::string>& warnings) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(p, ec))) return std::nullopt;
  const config::FileText file = config::readRegularFile(p.string(), max_bytes, expected);
  if (!file.error.empty()) {
    warnings.push_back(file.error + "; left out of the export");
    return std::nullopt;
  }
  return file.text;
}

}  // namespace

std::string defaultExportPath(const std::string& target) {
  std::error_code ec;
  const fs::path log = fs::is_directory(target, ec) ? fs::path(target) / "run.lcm" : fs::path(target);
  return fs::path(log).replace_extension(".h5").string();
}

HdfExport exportHdf5(const std::string& target, const std::string& out_path, bool force) {
  std::error_code ec;
  const fs::path log = fs::is_directory(target, ec) ? fs::path(target) / "run.lcm" : fs::path(target);
  if (const util::InputFile file =
          util::InputFile::open(log.string(), "a run directory (lagrange run --out) or its run.lcm");
      !file.ok())
    throw BadInput(file.error());
  const fs::path dir = log.parent_path();
  // Beside the log unless asked otherwise: RUN/run.h5 for a run folder.
  const std::string out_file = out_path.empty() ? defaultExportPath(target) : out_path;
  if (fs::exists(fs::symlink_status(out_file)) && !force)
    throw BadInput(out_file + " exists; expected a new file name (or --force to replace it)");
  util::checkOutputPath(out_file);  // never through a link planted there

  HdfExport result;
  result.path = out_file;
  // Pass 1: each channel's ticks and its fields' shapes; the run's identity.
  std::map<std::string, ChannelTable> tables;
  TrackingExport tracking;
  std::optional<std::string> logged_scenario;
  int64_t run_id = 0;
  result.scan = logs::readLog(log.string(), [&](const lcm::LogEvent& ev) {
    if (ev.channel == transport::kScenario && !logged_scenario) logged_scenario = logs::scenarioYaml(ev);
    withMessage(ev, [&](const auto& m) {
      ChannelTable& c = tables[ev.channel];
      if (c.ticks.empty() && c.fields.empty()) {
        ShapeVisitor shapes;
        transport::fields(shapes, m);
        c.fields = shapes.fields;
        run_id = m.header.run_id;
      }
      c.ticks.push_back(m.header.tick);
      using Message = std::decay_t<decltype(m)>;
      if constexpr (std::is_same_v<Message, lagrange::plant_truth_t>)
        tracking.seeTruth(m.header.tick, m.q.size());
      if constexpr (std::is_same_v<Message, lagrange::control_command_t>)
        tracking.seeCommand(m.header.tick, m.q_desired.size());
    });
  });
  for (auto& [channel, c] : tables) {
    std::sort(c.ticks.begin(), c.ticks.end());
    c.ticks.erase(std::unique(c.ticks.begin(), c.ticks.end()), c.ticks.end());
    c.written.assign(c.ticks.size(), false);
  }

  const std::optional<std::string> resolved =
      runFileText(dir / "config.resolved.yaml", static_cast<std::uintmax_t>(logs::maxScenarioEventBytes()),
                  "the run's resolved scenario", result.warnings);
  const std::optional<std::string> scenario_text = resolved ? resolved : logged_scenario;
  const std::optional<std::string> summary =
      runFileText(dir / "summary.json", kMaxSummaryBytes, "the run's summary.json", result.warnings);
  std::vector<std::string> joint_names;
  std::optional<double> tick_period;  // /tracking's t: the log's own scenario's, as Run.tracking's
  if (scenario_text) {
    try {
      const config::Scenario s = config::parseLoggedScenario(*scenario_text, "the run's scenario");
      joint_names = s.robotModel()->jointNames();
      tick_period = s.tickPeriod();
    } catch (const std::exception& e) {
      result.warnings.push_back(std::string("joint_names left out: the run's scenario does not read (") +
                                e.what() + ")");
    }
  }
  if (logged_scenario && logged_scenario != scenario_text) {
    try {
      tick_period = config::parseLoggedScenario(*logged_scenario, "the log's scenario").tickPeriod();
    } catch (const std::exception&) {
      // The resolved scenario's period, if it read; else /tracking has no t (said below).
    }
  }
  {
    const auto truth = tables.find(transport::kPlantTruth);
    const auto command = tables.find(transport::kControlCommand);
    size_t joints = 0, stages = 0;
    if (truth != tables.end())
      for (const FieldShape& f : truth->second.fields)
        if (f.name == "q") joints = f.size();
    if (command != tables.end())
      for (const FieldShape& f : command->second.fields)
        if (f.name == "xi_error" && f.dims.size() == 2 && f.dims[1] == joints) stages = f.dims[0];
    tracking.plan(joints, stages, tick_period);
  }

  const std::string partial = out_file + ".partial-" + std::to_string(getpid());
  H5::Exception::dontPrint();
  try {
    {
      H5::H5File file(partial, H5F_ACC_EXCL);
      H5::Group root = file.openGroup("/");
      textAttribute(root, "format", kFormat);
      textAttribute(root, "source", fs::absolute(log).lexically_normal().string());
      textAttribute(root, "run_id", std::to_string(run_id));
      if (scenario_text) textAttribute(root, "scenario", *scenario_text);
      if (summary) textAttribute(root, "summary", *summary);
      if (!joint_names.empty()) textListAttribute(root, "joint_names", joint_names);
      for (auto& [channel, c] : tables) {
        const hsize_t n = c.ticks.size();
        c.group = file.createGroup("/" + channel);
        c.tick = dataset(c.group, "tick", H5::PredType::NATIVE_INT64, {n}, "tick", "the sample's tick");
        c.t = dataset(c.group, "t", H5::PredType::NATIVE_DOUBLE, {n}, "s", "header.sim_time");
        c.utime = dataset(c.group, "publish_utime", H5::PredType::NATIVE_INT64, {n}, "us",
                          "header.publish_utime: the run's clock when it was published");
        for (const FieldShape& f : c.fields) {
          std::vector<hsize_t> dims = {n};
          dims.insert(dims.end(), f.dims.begin(), f.dims.end());
          c.datasets.push_back(f.size() > 0
                                   ? dataset(c.group, f.name, H5::PredType::NATIVE_DOUBLE, dims, f.unit, "")
                                   : H5::DataSet());
        }
      }
      if (tracking.wanted()) tracking.create(file);
      // Pass 2: the first intact copy of each tick, into its row.
      size_t held_values = 0;
      logs::readLog(log.string(), [&](const lcm::LogEvent& ev) {
        withMessage(ev, [&](const auto& m) {
          ChannelTable& c = tables.at(ev.channel);
          const size_t row = static_cast<size_t>(
              std::lower_bound(c.ticks.begin(), c.ticks.end(), m.header.tick) - c.ticks.begin());
          // A later copy of a tick; or a tick the first pass did not see (the log grew between them).
          if (row >= c.ticks.size() || c.ticks[row] != m.header.tick || c.written[row]) return;
          c.written[row] = true;
          using Message = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<Message, lagrange::plant_truth_t>) tracking.truth(m.header.tick, m.q);
          if constexpr (std::is_same_v<Message, lagrange::control_command_t>)
            tracking.command(m.header.tick, m.q_desired, m.xi_error);
          FlatVisitor flat{c.fields, {}, 0, false};
          transport::fields(flat, m);
          if (flat.misshapen) ++c.misshapen;
          held_values += flat.values.size();
          c.held[row] = {m.header.tick, m.header.publish_utime, m.header.sim_time, std::move(flat.values)};
          // Rows have their places: any order is right. Bounded by rows and by values held.
          if (c.held.size() >= kHeldRows || held_values >= kHeldValues) {
            for (auto& [name, table] : tables) flush(table);
            held_values = 0;
          }
        });
      });
      for (auto& [channel, c] : tables) {
        flush(c);
        result.channels.push_back({channel, static_cast<long long>(c.ticks.size())});
        if (c.misshapen > 0)
          result.warnings.push_back(
              channel + ": " + std::to_string(c.misshapen) +
              " messages had a field of another size than the first message's; their values "
              "there are NaN");
      }
      if (tracking.wanted()) {
        tracking.flush();
        result.channels.push_back({"tracking", static_cast<long long>(tracking.rows())});
      }
      for (const std::string& w : tracking.warnings()) result.warnings.push_back(w);
      file.close();
    }
    fs::rename(partial, out_file);
  } catch (const H5::Exception& e) {
    fs::remove(partial, ec);
    throw RuntimeFault("HDF5 could not write " + out_file + ": " + e.getDetailMsg());
  } catch (...) {
    fs::remove(partial, ec);
    throw;
  }
  return result;
}

}  // namespace lagrange::tools
