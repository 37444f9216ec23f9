/// @file
/// The logger process: records every LCM channel of the run to a standard LCM
/// event log (readable by lcm-logplayer and lcm::LogFile), computes the
/// tracking metrics live, and writes summary.json at the end.
///
///   .* -> LogFile (flushed at least every 100 ms)
///   PLANT_TRUTH, ACTUATOR_STATE -> TrackingMetrics -> STATUS (progress, flow control)
///   STATUS of every process -> summary.json "messages" and "processes"
///
/// The first event of the log is the resolved scenario on channel SCENARIO,
/// so a log describes itself.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "controller/gain_report_json.hpp"
#include "logger/error_line.hpp"
#include "logger/logger_loop.hpp"
#include "runtime/process.hpp"

namespace lagrange {
namespace {

constexpr int kLoggerReceiveBuffer = 4 << 20;

int DoMain(int argc, char** argv) {
  logger::LoggerOptions options;
  std::string gains_path;
  controller::GainReport gains;
  return runtime::runProcess(
      "logger", "Records every LCM channel to run.lcm and writes summary.json.", argc, argv,
      {{"-o,--out", &options.out_dir, "Directory for run.lcm and summary.json", true},
       {"--finish-grace", &options.finish_grace,
        "Seconds to wait for the other processes' final STATUS after the plant finished", true},
       {"--progress-fd", &options.progress_fd,
        "File descriptor to write progress lines to (\"SIM_TIME ERROR\" every 100 ms); the launcher uses it "
        "for its progress display"},
       {"--gains", &gains_path,
        "The launcher's gain report of this scenario (OUT/gains.json) for summary.json, instead of checking "
        "the gains again"}},
      // The gain report goes into summary.json; read (or computed) here,
      // under the normal scheduler (runtime/process.hpp).
      [&](const config::Scenario& s) {
        // Before any thread starts (LCM's receive thread inherits it).
        if (s.mode == config::Mode::kLockstep)
          runtime::niceAtLeast(s.lockstep.logger_nice, "lockstep.logger_nice");
        controller::ProcessGainReport handed = controller::processGainReport(s, gains_path);
        if (!handed.note.empty()) spdlog::warn(fmt::format("{}", handed.note));
        gains = std::move(handed.report);
        if (handed.sampled) gains.sampled = *handed.sampled;  // else the logger checks it at the end
      },
      [&](const config::Scenario& s, transport::LcmNode& node) {
        try {
          return logger::runLogger(s, node, options, gains);
        } catch (const std::exception& e) {
          logger::sendErrorLine(options.progress_fd, e.what());  // for the launcher to print
          throw;
        }
      },
      // Every message of the run lands here: ask for a deep socket buffer.
      kLoggerReceiveBuffer);
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
