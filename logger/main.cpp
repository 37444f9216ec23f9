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

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "config/scenario_lcm.hpp"
#include "controller/gain_report.hpp"
#include "logger/event_log.hpp"
#include "logger/summary.hpp"
#include "logger/tick_coverage.hpp"
#include "logger/tracking_metrics.hpp"
#include "runtime/process.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kLoggerReceiveBuffer = 4 << 20;

int DoMain(int argc, char** argv) {
  std::string out_dir = ".";
  double finish_grace = 2.0;
  int progress_fd = -1;
  return runtime::runProcess(
      "logger", "Records every LCM channel to run.lcm and writes summary.json.", argc, argv,
      [&](CLI::App& app) {
        app.add_option("-o,--out", out_dir, "Directory for run.lcm and summary.json")->capture_default_str();
        app.add_option("--finish-grace", finish_grace,
                       "Seconds to wait for the other processes' final STATUS after the plant finished")
            ->capture_default_str();
        app.add_option("--progress-fd", progress_fd,
                       "File descriptor to write progress lines to (\"SIM_TIME ERROR\" every 100 ms); "
                       "the launcher uses it for its progress display");
      },
      [&](const config::Scenario& s, transport::LcmNode& node) {
        const auto wall_start = Clock::now();
        const std::string log_path = (std::filesystem::path(out_dir) / "run.lcm").string();
        logger::EventLog log(log_path);
        const lagrange::scenario_t scenario = config::scenarioMessage(s);
        log.writeMessage(transport::kScenario, scenario, transport::nowUtime());

        // The sampled-data check waits for the summary: at start it would delay
        // this process while a realtime run's first ticks go by.
        controller::GainReport gains = controller::checkGains(s, false);
        logger::TrackingMetrics metrics(model::Reference(s.reference), s.metrics.tolerance,
                                        s.metrics.xi_tolerance);
        runtime::StatusReporter status(node);
        logger::RunFacts facts;
        facts.log_path = log_path;
        facts.run_id = node.runId();
        const int n = s.dof();

        // Record first, then interpret: the log keeps every message, even ones
        // the validators below reject. Every channel but LCM's own self-test:
        // LCM 1.3.1 queues LCM_SELF_TEST without counting it for subscribers,
        // then lets it consume the queue count of a '.*' subscription, which
        // then silently skips the next counted message -- the first samples of
        // a run went missing from run.lcm that way (one run in ~50).
        // SCENARIO too is left out: the log starts with it (above), and the
        // copies this logger publishes for stock loggers need no recording.
        node.subscribeRaw("(?!LCM_SELF_TEST$|SCENARIO$).*", [&](const lcm::ReceiveBuffer* rbuf,
                                                                const std::string& channel) {
          log.write(channel, rbuf->data, static_cast<int>(rbuf->data_size), rbuf->recv_utime);
        });
        // Which ticks of each per-tick channel reached the log intact
        // (summary.json log.missing_ticks). Every copy counts, in any order:
        // one re-sent by the plant, or overtaken by a later one, is still a
        // message of the run.
        constexpr auto kAnyOrder = transport::LcmNode::Order::kAcceptReordered;
        std::map<std::string, logger::TickCoverage> coverage;
        for (const char* channel : {transport::kPlantPosition, transport::kPlantTruth,
                                    transport::kControlCommand, transport::kActuatorState})
          coverage.emplace(channel, logger::TickCoverage(s.lastTick()));
        if (s.flexible) coverage.emplace(transport::kPlantMotor, logger::TickCoverage(s.lastTick()));
        // What STATUS last_tick confirms to the plant. In lockstep: every
        // message of every tick up to it is in the log; the plant re-sends
        // the ticks after it (and the controller and actuator answer them
        // again), so a datagram lost on the way to the logger alone is sent
        // again. In realtime (nothing is re-sent): the contiguous samples.
        auto confirmed = [&] {
          int64_t tick = metrics.lastTick();
          if (s.mode == config::Mode::kLockstep)
            for (const auto& entry : coverage) tick = std::min(tick, entry.second.contiguousThrough());
          return tick;
        };
        // Acknowledge progress often enough that the plant, allowed
        // lockstep.logger_window ticks ahead, never waits for the logger.
        const long long ack_every = std::max(1, s.lockstep.logger_window / 4);
        bool progress_due = false;
        long long acked = -1;  // the last_tick of the last STATUS
        auto record = [&](const char* channel, int64_t tick) {
          coverage.at(channel).add(tick);
          if (confirmed() - acked >= ack_every) progress_due = true;
        };
        node.subscribe<lagrange::plant_truth_t>(
            transport::kPlantTruth, [n](const auto& m) { return transport::validate(m, n); },
            [&](const lagrange::plant_truth_t& m) {
              metrics.addSample(m.header.tick, m.header.sim_time, transport::toEigen(m.q));
              record(transport::kPlantTruth, m.header.tick);
            },
            kAnyOrder);
        node.subscribe<lagrange::plant_position_t>(
            transport::kPlantPosition, [n](const auto& m) { return transport::validate(m, n); },
            [&](const lagrange::plant_position_t& m) { record(transport::kPlantPosition, m.header.tick); },
            kAnyOrder);
        if (s.flexible)
          node.subscribe<lagrange::plant_motor_t>(
              transport::kPlantMotor,
              [n, rates = s.flexible->rate_sensor](const auto& m) {
                return transport::validate(m, n, rates);
              },
              [&](const lagrange::plant_motor_t& m) { record(transport::kPlantMotor, m.header.tick); },
              kAnyOrder);
        node.subscribe<lagrange::control_command_t>(
            transport::kControlCommand, [n](const auto& m) { return transport::validate(m, n); },
            [&](const lagrange::control_command_t& m) {
              metrics.addChainErrors(m.header.tick, m.header.sim_time, m.xi_error);
              record(transport::kControlCommand, m.header.tick);
            },
            kAnyOrder);
        node.subscribe<lagrange::actuator_state_t>(
            transport::kActuatorState, [n](const auto& m) { return transport::validate(m, n); },
            [&](const lagrange::actuator_state_t& m) {
              metrics.addTorque(transport::toEigen(m.tau_applied));
              record(transport::kActuatorState, m.header.tick);
            },
            kAnyOrder);
        std::optional<Clock::time_point> plant_finished_at, all_samples_at;
        node.subscribe<lagrange::status_t>(
            transport::kStatus, [](const auto& m) { return transport::validate(m); },
            [&](const lagrange::status_t& m) {
              if (m.process == "logger") return;
              facts.final_status[m.process] = m;
              if (m.process == "plant" && m.state == "finished" && !plant_finished_at)
                plant_finished_at = Clock::now();
            });

        // Best effort: a full pipe drops a line, never blocks the logger.
        auto write_progress = [&] {
          if (progress_fd < 0) return;
          const std::string line =
              std::to_string(metrics.lastTime()) + " " + std::to_string(metrics.lastError()) + "\n";
          [[maybe_unused]] const ssize_t written = write(progress_fd, line.data(), line.size());
        };
        auto report = [&](const char* state) {
          acked = confirmed();
          status.publish(state, acked, static_cast<double>(std::max<int64_t>(acked, 0)) * s.tickPeriod(),
                         metrics.lastError());
        };
        // True when plant, controller and actuator have all reported `state`
        // (or, with state empty, any final state).
        auto all_reported = [&](const std::string& state) {
          for (const char* p : {"plant", "controller", "actuator"}) {
            auto it = facts.final_status.find(p);
            if (it == facts.final_status.end()) return false;
            const std::string& reported = it->second.state;
            if (state.empty() ? (reported == "ready" || reported == "running") : reported != state)
              return false;
          }
          return true;
        };

        report("ready");
        // The scenario on LCM, now and every second: a stock lcm-logger
        // started before or during the run records it, so its log replays.
        auto next_scenario = Clock::now();
        auto next_flush = Clock::now() + std::chrono::milliseconds(100);
        auto next_status = Clock::now() + std::chrono::milliseconds(100);
        auto next_progress_line = Clock::now();
        while (!runtime::stopRequested()) {
          node.handle(20);
          const auto now = Clock::now();
          if (now >= next_scenario) {
            node.publish(transport::kScenario, scenario);
            next_scenario = now + std::chrono::seconds(1);
          }
          if (now >= next_flush) {
            log.flush();
            next_flush = now + std::chrono::milliseconds(100);
          }
          if (progress_due || now >= next_status) {
            report("running");
            if (now >= next_progress_line) {
              next_progress_line = now + std::chrono::milliseconds(100);
              write_progress();
            }
            progress_due = false;
            next_status = now + std::chrono::milliseconds(100);
          }
          if (plant_finished_at && (all_reported("finished") ||
                                    now - *plant_finished_at > std::chrono::duration<double>(finish_grace)))
            break;
          // The plant's final STATUS can be lost like any datagram: having
          // every tick's sample is enough to finish, after the same grace.
          if (confirmed() >= s.lastTick()) {
            if (!all_samples_at) all_samples_at = now;
            if (now - *all_samples_at > std::chrono::duration<double>(finish_grace)) break;
          }
        }
        // Drain what is still queued, then close the log before the summary.
        // Bounded in time: other traffic on the URL (another publisher, a
        // flood) must not keep the logger from finishing. When interrupted,
        // the others are stopping too: wait (up to the grace) for their final
        // STATUS so the summary says how each ended.
        const auto drain_until =
            Clock::now() + (runtime::stopRequested() ? std::chrono::duration<double>(finish_grace)
                                                     : std::chrono::duration<double>(0.2));
        while (Clock::now() < drain_until) {
          const bool got = node.raw().handleTimeout(10) > 0;
          if (!got && (!runtime::stopRequested() || all_reported(""))) break;
        }
        // Completed means every tick was recorded, however the logger was stopped.
        // (Realtime runs do not re-send: a sample lost on the way is missing
        // from the log -- log.missing_samples -- but the run still completed.)
        facts.status = metrics.newestTick() >= s.lastTick() ? "completed" : "interrupted";
        if (facts.status == "completed" && !all_reported("finished"))
          spdlog::warn("not every process reported 'finished' within {} s of the plant", finish_grace);
        report(runtime::stopRequested() ? "interrupted" : "finished");
        write_progress();  // the final sample, for the launcher's last progress line
        log.flush();
        facts.log_events = log.events();
        for (const auto& [channel, ticks] : coverage)
          facts.missing_ticks[channel] = ticks.missingUpTo(metrics.newestTick());
        lagrange::status_t own{};  // zeroed: its loop statistics are not measured
        own.process = "logger";
        own.state = facts.status == "completed" ? "finished" : "interrupted";
        own.last_tick = metrics.lastTick();
        own.channels = node.channelStats();
        own.num_channels = static_cast<int32_t>(own.channels.size());
        facts.final_status["logger"] = own;
        facts.wall_time = std::chrono::duration<double>(Clock::now() - wall_start).count();

        gains.sampled = controller::checkSampledData(s);
        const auto summary = logger::makeSummary(s, metrics.summary(), gains, facts);
        const std::string summary_path = (std::filesystem::path(out_dir) / "summary.json").string();
        std::ofstream out(summary_path);
        out << summary.dump(2) << "\n";
        if (!out) throw std::runtime_error("cannot write '" + summary_path + "'");
        spdlog::info("wrote {} events to {} and {}", facts.log_events, log_path, summary_path);
        return 0;
      },
      // Every message of the run lands here: ask for a deep socket buffer.
      kLoggerReceiveBuffer);
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
