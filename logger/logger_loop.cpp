#include "logger/logger_loop.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

#include "config/robot_description_lcm.hpp"
#include "config/scenario_lcm.hpp"
#include "controller/gain_report.hpp"
#include "logger/answer_times.hpp"
#include "logger/arrival_timing.hpp"
#include "logger/error_line.hpp"
#include "logger/event_log.hpp"
#include "logger/metrics_lcm.hpp"
#include "logger/record_filter.hpp"
#include "logger/record_gaps.hpp"
#include "logger/run_end.hpp"
#include "logger/summary.hpp"
#include "logger/tick_confirmation.hpp"
#include "logger/tracking_metrics.hpp"
#include "runtime/process.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace lagrange::logger {
namespace {

using Clock = std::chrono::steady_clock;

Clock::duration asDuration(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// The validation of the logger's inputs: the run's joints; PLANT_MOTOR with
// the rate row the scenario promises.
// Every per-tick message keeps the run's clock: a tick of the scenario's,
// its sim_time that tick's (transport::validateClock).
template <class Msg>
transport::Rejection validateFor(const config::Scenario& s, const Msg& m) {
  if (std::string why = transport::validateClock(m.header, s.lastTick(), s.tickPeriod()); !why.empty())
    return why;
  if constexpr (std::is_same_v<Msg, lagrange::plant_motor_t>)
    return transport::validate(m, s.dof(), s.flexible->rate_sensor);
  else
    return transport::validate(m, s.dof());
}

// Best effort: a full pipe drops a line, never blocks the logger.
void writeProgress(int fd, const TrackingMetrics& metrics) {
  if (fd < 0) return;
  const std::string line =
      std::to_string(metrics.lastTime()) + " " + std::to_string(metrics.lastError()) + "\n";
  [[maybe_unused]] const ssize_t written = write(fd, line.data(), line.size());
}

// Who answers whom, for the slow-answer lines: a program from outside by
// its command line. In lockstep the plant answers each ACTUATOR_STATE with
// its next tick's position; in realtime it runs on its own clock and asks
// nobody, so only the others are timed there.
std::string programOf(const std::string& builtin, const std::vector<std::string>& command) {
  if (command.empty()) return builtin;
  std::string program;
  for (const std::string& arg : command) program += (program.empty() ? "" : " ") + arg;
  return program.size() > 120 ? program.substr(0, 117) + "..." : program;
}

std::vector<AnswerTimes::Answerer> answerersOf(const config::Scenario& s) {
  const std::vector<std::string> none;
  std::vector<AnswerTimes::Answerer> out = {
      {"controller",
       programOf("lagrange-controller", s.controller.type == "external" ? s.controller.command : none),
       transport::kPlantPosition, transport::kControlCommand},
      {"actuator", "lagrange-actuator", transport::kControlCommand, transport::kActuatorState}};
  if (s.mode == config::Mode::kLockstep)
    out.push_back({"plant", programOf("lagrange-plant", s.plant.external() ? s.plant.command : none),
                   transport::kActuatorState, transport::kPlantPosition, 1});
  return out;
}

}  // namespace

int runLogger(const config::Scenario& s, transport::LcmNode& node, const LoggerOptions& options,
              controller::GainReport gains) {
  const auto wall_start = Clock::now();
  const std::string log_path = (std::filesystem::path(options.out_dir) / "run.lcm").string();
  EventLog log(log_path);
  const lagrange::scenario_t scenario = config::scenarioMessage(s);
  log.writeMessage(transport::kScenario, scenario, transport::nowUtime());
  const lagrange::robot_description_t robot = config::robotDescriptionMessage(s);
  log.writeMessage(transport::kRobotDescription, robot, transport::nowUtime());

  TrackingMetrics metrics(model::Reference(s.reference), s.metrics.tolerance, s.metrics.xi_tolerance,
                          s.tickPeriod());
  watchLimits(metrics, s);
  runtime::StatusReporter status(node);
  RunFacts facts;
  facts.log_path = log_path;
  facts.run_id = node.runId();
  facts.nice = runtime::niceValue();
  const std::vector<std::string> per_tick =
      transport::perTickChannels({s.flexible.has_value(), s.velocitySensor()});
  TickConfirmation confirmation(per_tick, s.lastTick(), s.mode == config::Mode::kLockstep,
                                s.lockstep.logger_window);
  RunEnd end(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.finish_grace)),
             Clock::now());
  // The plant never waits longer than this without sending anything (it
  // re-sends what is unanswered meanwhile): past it, it is gone. At the
  // start, twice the plant's own start-up allowance (3 x stall_timeout).
  const double plant_silence_limit = 4.0 * s.lockstep.stall_timeout;
  const double plant_start_limit = 6.0 * s.lockstep.stall_timeout;
  AnswerTimes answers(answerersOf(s), s.supervision.slow_answer);
  // An external controller in realtime: its loop timed from its commands.
  const bool external_loop = s.controller.type == "external" && s.mode == config::Mode::kRealtime;
  ArrivalTiming command_arrivals(s.tickPeriod());
  const auto sinceStart = [wall_start](Clock::time_point t) {
    return std::chrono::duration<double>(t - wall_start).count();
  };
  std::set<std::string> refusal_said;  // channels whose refused sender was said on the terminal
  RecordGaps gaps;  // what the log lacks of the run's messages (summary.json log.missing_records)
  RecordFilter record_filter(node.runId(), s.lastTick());  // only what the run's processes would accept

  // Record first, then interpret: the log keeps every message, even ones
  // the validators below reject. Every channel but LCM's own self-test:
  // LCM 1.3.1 queues LCM_SELF_TEST without counting it for subscribers,
  // then lets it consume the queue count of a '.*' subscription, which
  // then silently skips the next counted message -- the first samples of
  // a run went missing from run.lcm that way (one run in ~50).
  // SCENARIO too is left out: the log starts with it (above), and the
  // copies this logger publishes for stock loggers need no recording; and
  // RUN_JOIN, the launchers' agreement before the run (signed with another key).
  // Of the project's channels, only what the run's processes would accept
  // by its header is recorded (logger/record_filter.hpp).
  node.subscribeRaw("(?!LCM_SELF_TEST$|SCENARIO$|RUN_JOIN$).*", [&](const lcm::ReceiveBuffer* rbuf,
                                                                    const std::string& channel) {
    if (!record_filter.admit(channel, rbuf->data, rbuf->data_size, node.oversized(channel, rbuf->data_size)))
      return;
    log.write(channel, rbuf->data, static_cast<int>(rbuf->data_size), rbuf->recv_utime);
    gaps.recorded(channel, rbuf->data, rbuf->data_size, node.runId());
  });
  // Every per-tick channel the same way: the metrics take what they need
  // (metrics_lcm.hpp), then the tick counts as recorded. Every copy counts,
  // in any order: one re-sent by the plant, or overtaken by a later one, is
  // still a message of the run.
  for (const std::string& channel : per_tick) {
    transport::withChannelMessage(channel, false, [&](auto type) {
      using Msg = decltype(type);
      node.subscribe<Msg>(
          channel,
          [&, channel](const Msg& m) {
            std::string why = validateFor(s, m);
            // A refused sender is said at once, once a channel: in lockstep
            // the plant then waits for a confirmation that cannot come, and
            // its stall alone would not say whose value it was.
            if (!why.empty() && refusal_said.insert(channel).second) {
              const std::string line = fmt::format(
                  "the logger refuses {} from the {}: {} (each such message is counted as invalid in "
                  "summary.json messages.{})",
                  channel, m.header.publisher, why, channel);
              spdlog::warn(line);
              sendNoticeLine(options.progress_fd, line);
            }
            return why;
          },
          [&, channel](const Msg& m) {
            if (m.header.publisher == "plant") end.plantHeard(Clock::now());
            answers.arrived(channel, m.header.tick, sinceStart(Clock::now()));
            if (external_loop && channel == transport::kControlCommand)
              command_arrivals.arrived(m.header.tick, sinceStart(Clock::now()));
            observe(metrics, m);
            confirmation.record(channel, m.header.tick, metrics.lastTick());
          },
          transport::LcmNode::Order::kAcceptReordered);
      return true;
    });
  }
  node.subscribe<lagrange::status_t>(
      transport::kStatus, [](const auto& m) { return transport::validate(m); },
      [&](const lagrange::status_t& m) {
        if (m.process == "logger") return;
        if (m.process == "plant") end.plantHeard(Clock::now());
        facts.final_status[m.process] = m;
        // validate() admitted only known states
        end.processState(m.process, *util::enumFrom(transport::kProcessStateNames, m.state), Clock::now());
      });

  auto report = [&](runtime::State state) {
    const int64_t acked = confirmation.acknowledge(metrics.lastTick());
    status.publish(state, acked, static_cast<double>(std::max<int64_t>(acked, 0)) * s.tickPeriod(),
                   metrics.lastError());
  };
  report(runtime::State::kReady);
  // The scenario and the robot on LCM, now and every second: a stock
  // lcm-logger started before or during the run records them, so its log
  // replays and draws; a viewer joining a running scenario learns the arm.
  auto next_scenario = Clock::now();
  auto next_flush = Clock::now() + std::chrono::milliseconds(100);
  auto next_status = Clock::now() + std::chrono::milliseconds(100);
  auto next_progress_line = Clock::now();
  std::optional<std::string> plant_gone;  // why the plant is taken for gone (it ends the run)
  while (!runtime::stopRequested()) {
    node.handle(20);
    log.check();  // a write error (full disk) stops the run, naming run.lcm and the error
    const auto now = Clock::now();
    if (now >= next_scenario) {
      node.publish(transport::kScenario, scenario);
      node.publish(transport::kRobotDescription, robot);
      next_scenario = now + std::chrono::seconds(1);
    }
    if (now >= next_flush) {
      log.flush();
      next_flush = now + std::chrono::milliseconds(100);
    }
    if (confirmation.acknowledgementDue() || now >= next_status) {
      report(runtime::State::kRunning);
      if (now >= next_progress_line) {
        next_progress_line = now + std::chrono::milliseconds(100);
        writeProgress(options.progress_fd, metrics);
      }
      next_status = now + std::chrono::milliseconds(100);
    }
    // While the plant runs: after its last tick nothing more is asked, and
    // an answer it no longer needs is not late.
    const bool plant_running = metrics.newestTick() < s.lastTick();
    for (const AnswerTimes::Slow& slow :
         plant_running ? answers.newlySlow(sinceStart(now)) : std::vector<AnswerTimes::Slow>{}) {
      const std::string line =
          fmt::format("the {} ({}) has not answered tick {} for {:.1f} s (supervision.slow_answer = {:g} s)",
                      slow.name, slow.program, slow.tick, slow.waited, s.supervision.slow_answer);
      spdlog::warn(line);
      sendNoticeLine(options.progress_fd, line);  // for the launcher to print now
    }
    if (end.due(now, confirmation.confirmed(metrics.lastTick()) >= s.lastTick())) break;
    if (const auto silent =
            end.plantGone(now, asDuration(plant_silence_limit), asDuration(plant_start_limit))) {
      plant_gone = fmt::format(
          "the plant has not been heard for {:.0f} s ({} is allowed: {}); its process or its host is gone, "
          "or "
          "never started (last tick recorded: {}). The log so far is kept in {}",
          std::chrono::duration<double>(*silent).count(),
          end.plantEverHeard() ? fmt::format("{:g} s", plant_silence_limit)
                               : fmt::format("{:g} s at the start", plant_start_limit),
          end.plantEverHeard() ? "4 x lockstep.stall_timeout; it re-sends or reports well within that"
                               : "6 x lockstep.stall_timeout, twice the plant's own start-up allowance",
          metrics.lastTick(), log_path);
      break;  // the log and summary.json are written, then the run is stopped (below)
    }
  }
  // Drain what is still queued, then close the log before the summary.
  // Bounded in time: other traffic on the URL (another publisher, a
  // flood) must not keep the logger from finishing. When interrupted,
  // the others are stopping too: wait (up to the grace) for their final
  // STATUS so the summary says how each ended.
  const auto drain_until =
      Clock::now() + (runtime::stopRequested() ? std::chrono::duration<double>(options.finish_grace)
                                               : std::chrono::duration<double>(0.2));
  while (Clock::now() < drain_until) {
    const bool got = node.raw().handleTimeout(10) > 0;
    if (!got && (!runtime::stopRequested() || end.allEnded())) break;
  }
  // Completed means every tick was recorded, however the logger was stopped:
  // in lockstep every one up to the last (the plant re-sends until the
  // logger confirms, so a gap is a plant that skipped ticks -- one that
  // jumps to its last tick and says "finished" has not run the scenario).
  // Realtime runs do not re-send: a sample lost on the way is missing from
  // the log (log.missing_ticks; the verdict weighs it) but the run still
  // completed when its last tick came.
  const long long recorded_up_to =
      s.mode == config::Mode::kLockstep ? metrics.lastTick() : metrics.newestTick();
  facts.status = recorded_up_to >= s.lastTick() ? "completed" : "interrupted";
  if (facts.status == "completed" && !end.allReported(runtime::State::kFinished))
    spdlog::warn(
        fmt::format("not every process reported 'finished' within {} s of the plant", options.finish_grace));
  // A plant taken for gone ends the logger as interrupted, whatever it recorded.
  report(runtime::stopRequested() || plant_gone ? runtime::State::kInterrupted : runtime::State::kFinished);
  writeProgress(options.progress_fd, metrics);  // the final sample, for the launcher's last progress line
  log.close();  // throws naming run.lcm if its last bytes could not be written
  facts.log_events = log.events();
  facts.missing_ticks = confirmation.missingUpTo(metrics.newestTick());
  lagrange::status_t own{};  // zeroed: its loop statistics are not measured
  own.process = "logger";
  own.state = transport::toString(facts.status == "completed" && !plant_gone ? runtime::State::kFinished
                                                                             : runtime::State::kInterrupted);
  own.last_tick = metrics.lastTick();
  own.channels = node.channelStats();
  own.num_channels = static_cast<int32_t>(own.channels.size());
  facts.final_status["logger"] = own;
  facts.wall_time = std::chrono::duration<double>(Clock::now() - wall_start).count();
  facts.missing_records = gaps.missing(facts.final_status);
  facts.not_recorded = record_filter.notRecorded();
  facts.answers = answers.summary();
  if (external_loop) facts.external_controller_loop = command_arrivals.loopJson();

  if (gains.sampled.verdict.empty()) gains.sampled = controller::checkSampledData(s);
  const auto summary = makeSummary(s, metrics.summary(), gains, facts);
  const std::string summary_path = (std::filesystem::path(options.out_dir) / "summary.json").string();
  util::writeOutputFile(summary_path, summary.dump(2) + "\n");  // throws naming the file and the error
  spdlog::info(fmt::format("wrote {} events to {} and {}", facts.log_events, log_path, summary_path));
  // A plant gone silent ends the run as an error, after its summary: the
  // launcher marks it failed with this reason (tools/run/run_command.cpp).
  if (plant_gone) throw RuntimeFault(*plant_gone);
  return 0;
}

}  // namespace lagrange::logger
