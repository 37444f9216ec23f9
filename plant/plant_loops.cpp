#include "plant/plant_loops.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <optional>

#include "plant/lockstep_protocol.hpp"
#include "plant/plant_lcm.hpp"
#include "plant/scenario_plant.hpp"
#include "plant/stall_diagnosis.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"
#include "transport/rate_loop.hpp"

namespace lagrange::plant {

using State = transport::ProcessState;

namespace {
using Clock = std::chrono::steady_clock;

// PLANT_POSITION with, for flexible joints, PLANT_MOTOR and, with a velocity
// sensor, PLANT_RATE of the same tick first, so a controller woken by the
// position finds them there.
void publishMeasurements(transport::LcmNode& node, const PlantSample& m) {
  if (m.motor) node.publish(transport::kPlantMotor, *m.motor);
  if (m.rate) node.publish(transport::kPlantRate, *m.rate);
  node.publish(transport::kPlantPosition, m.position);
}
}  // namespace

int runLockstep(const config::Scenario& s, transport::LcmNode& node, PlantSim& sim,
                runtime::StatusReporter& status) {
  const int n = s.dof();
  const int64_t last_tick = s.lastTick();
  ScenarioSensors sensors = sensorsFor(s);
  LockstepProtocol<PlantSample> protocol({last_tick, s.lockstep.logger_window,
                                          std::chrono::duration_cast<Clock::duration>(
                                              std::chrono::duration<double>(s.lockstep.retransmit_timeout))});

  const int torque_steps = s.torqueStepsPerTick();
  Eigen::MatrixXd tau = Eigen::MatrixXd::Zero(torque_steps, n);  // row j: held over step j of the period
  node.subscribe<lagrange::actuator_state_t>(
      transport::kActuatorState,
      [n, torque_steps](const auto& m) { return transport::validate(m, n, torque_steps); },
      [&](const lagrange::actuator_state_t& m) {
        if (protocol.actuatorState(m.header.tick)) tau = transport::toEigen(m.tau_applied);
      });
  std::map<std::string, lagrange::status_t> peers;  // the newest STATUS of each, for a stall's diagnosis
  node.subscribe<lagrange::status_t>(
      transport::kStatus, [](const auto& m) { return transport::validate(m); },
      [&](const lagrange::status_t& m) {
        if (m.process == "logger") protocol.loggerConfirmed(m.last_tick);
        if (m.process != "plant") peers[m.process] = m;
      });
  // Nothing waits forever (lockstep.stall_timeout); the first answer and the
  // logger's first word get the start-up time, while processes come up, and
  // so does any wait after a SIGCONT (runtime::takeResumeNotice: the plant
  // was stopped, or the launcher has restarted a peer that now starts up).
  const auto stall = std::chrono::duration<double>(s.lockstep.stall_timeout);
  const auto startup = std::chrono::duration<double>(startupTimeout(s));
  auto stalled = [&](int64_t k, Clock::time_point since) {
    return StallFacts{k, std::chrono::duration<double>(Clock::now() - since).count(), peers,
                      node.channelStats()};
  };
  // The measurements go with the truth: the controller and the actuator
  // answer a re-sent tick with what they sent for it, which the logger may
  // be the one to lack.
  auto resendForLogger = [&] {
    for (const PlantSample* sent : protocol.logResendsDue(Clock::now())) {
      publishMeasurements(node, *sent);
      node.publish(transport::kPlantTruth, sent->truth);
    }
  };

  status.publish(State::kReady, -1, 0.0);
  auto next_status = Clock::now();
  for (int64_t k = 0; k <= last_tick; ++k) {
    const double t = static_cast<double>(k) * s.tickPeriod();
    auto wait_start = Clock::now();
    protocol.awaitLogger(wait_start);
    bool resumed = false;
    while (!protocol.mayPublish(k) && !runtime::stopRequested()) {
      if (runtime::takeResumeNotice()) {
        wait_start = Clock::now();
        resumed = true;
      }
      if (Clock::now() - wait_start > (protocol.loggerHeard() && !resumed ? stall : startup))
        throw PlantStalled(describeLoggerStall(stalled(k, wait_start), protocol.loggerTick()));
      node.handle(5);
      resendForLogger();
    }
    if (runtime::stopRequested()) {
      status.publish(State::kInterrupted, k - 1, t);
      return 0;
    }
    const plant::TorqueInput input =
        k == 0 ? plant::TorqueInput{} : plant::TorqueInput{k - 1, lagrange::plant_truth_t::TORQUE_COMMANDED};
    const PlantSample out = measureTick(s, sensors, sim, k, t, tau.row(0).transpose(), input);
    publishMeasurements(node, out);
    node.publish(transport::kPlantTruth, out.truth);
    const auto published_at = Clock::now();
    protocol.published(k, out, published_at);
    if (Clock::now() >= next_status) {
      status.publish(State::kRunning, k, t);
      next_status = Clock::now() + std::chrono::milliseconds(500);
    }
    auto answer_deadline = published_at + (k == 0 ? startup : stall);
    while (!protocol.answered() && !runtime::stopRequested()) {
      if (runtime::takeResumeNotice())
        answer_deadline = std::max(answer_deadline, decltype(answer_deadline)(Clock::now() + startup));
      if (Clock::now() > answer_deadline) throw PlantStalled(describeAnswerStall(stalled(k, published_at)));
      node.handle(5);
      if (protocol.positionResendDue(Clock::now())) publishMeasurements(node, out);
    }
    if (runtime::stopRequested()) {
      status.publish(State::kInterrupted, k, t);
      return 0;
    }
    // The last tick's command is awaited too, so every message of the
    // ring is delivered before the plant reports "finished".
    if (k < last_tick) sim.stepProfile(tau, s.substepsPerTick());
  }
  // The end: every sample in the log first (bounded: a logger that has
  // gone away does not keep the plant forever).
  const auto log_deadline = Clock::now() + stall;
  protocol.awaitLogger(Clock::now());
  while (!protocol.allConfirmed() && Clock::now() < log_deadline && !runtime::stopRequested()) {
    node.handle(5);
    resendForLogger();
  }
  if (!protocol.allConfirmed())
    spdlog::warn(fmt::format("the logger confirmed every message up to tick {} of {}", protocol.loggerTick(),
                             last_tick));
  const long long retransmits = protocol.retransmits(), log_resends = protocol.logResends();
  if (retransmits > 0 || log_resends > 0)
    spdlog::info(
        fmt::format("re-sent {} position samples nobody answered, and {} ticks the logger had not confirmed",
                    retransmits, log_resends));
  // Three times: the others end on it, and a datagram can be lost.
  for (int copy = 0; copy < 3; ++copy)
    status.publish(
        State::kFinished, last_tick, static_cast<double>(last_tick) * s.tickPeriod(), std::nan(""),
        "retransmits=" + std::to_string(retransmits) + " log_resends=" + std::to_string(log_resends));
  return 0;
}

namespace {
// Waits for STATUS "ready" (or later) from every other process, so that no
// tick of a realtime run passes unheard.
void awaitPeers(transport::LcmNode& node, const std::map<std::string, lagrange::status_t>& heard,
                double timeout) {
  const auto start = Clock::now();
  while (heard.size() < 3 && !runtime::stopRequested()) {
    if (Clock::now() - start > std::chrono::duration<double>(timeout))
      throw PlantStalled(describeMissingPeers(
          {-1, std::chrono::duration<double>(Clock::now() - start).count(), heard, node.channelStats()},
          {"logger", "controller", "actuator"}));
    node.handle(20);
  }
}
}  // namespace

int runRealtime(const config::Scenario& s, transport::LcmNode& node, PlantSim& sim,
                runtime::StatusReporter& status) {
  const int n = s.dof();
  const int64_t last_tick = s.lastTick();
  ScenarioSensors sensors = sensorsFor(s);
  const int64_t max_age = s.realtime.max_torque_age;
  const int64_t hold_limit =
      s.realtime.stale_torque == config::StaleTorque::kHold ? max_age + s.realtime.hold_periods : max_age;

  // Publish times of recent position samples, for the end-to-end latency.
  constexpr int64_t kRing = 4096;
  std::array<int64_t, kRing> published_utime{};
  transport::SampleHistogram latencies, ages;  // fixed memory: nothing allocated per cycle

  const int torque_steps = s.torqueStepsPerTick();
  std::optional<lagrange::actuator_state_t> latest;
  node.subscribe<lagrange::actuator_state_t>(
      transport::kActuatorState,
      [n, torque_steps](const auto& m) { return transport::validate(m, n, torque_steps); },
      [&](const lagrange::actuator_state_t& m) {
        if (latest && m.header.tick <= latest->header.tick) return;
        latest = m;
        if (m.header.tick >= 0 && published_utime[m.header.tick % kRing] != 0)
          latencies.add(
              static_cast<double>(node.lastReceiveUtime() - published_utime[m.header.tick % kRing]) * 1e-6);
      });
  std::map<std::string, lagrange::status_t> peers;
  node.subscribe<lagrange::status_t>(
      transport::kStatus, [](const auto& m) { return transport::validate(m); },
      [&](const lagrange::status_t& m) {
        if (m.process == "logger" || m.process == "controller" || m.process == "actuator")
          peers[m.process] = m;
      });

  status.publish(State::kReady, -1, 0.0);
  awaitPeers(node, peers, startupTimeout(s));

  transport::FixedRateLoop loop(s.tickPeriod(), 0.0);
  int64_t used_tick = -1, missing = 0, held = 0, zeroed = 0;
  auto stats = [&] {
    lagrange::loop_stats_t st = loop.stats();
    transport::setInputStats(st, ages, missing, held + zeroed);
    const auto l = latencies.percentiles();
    st.torque_held = held;
    st.torque_zeroed = zeroed;
    st.latency_p50 = l.p50;
    st.latency_p99 = l.p99;
    st.latency_max = l.max;
    return st;
  };

  Eigen::MatrixXd tau =
      Eigen::MatrixXd::Zero(torque_steps, n);  // applied over the period ending at the sample
  plant::TorqueInput applied;                  // where tau came from
  loop.start();
  auto next_status = transport::monotonicNs() + 500'000'000LL;
  for (int64_t k = 0; k <= last_tick && !runtime::stopRequested(); ++k) {
    loop.waitNext();
    const double t = static_cast<double>(k) * s.tickPeriod();
    const PlantSample out = measureTick(s, sensors, sim, k, t, tau.row(0).transpose(), applied);
    publishMeasurements(node, out);
    node.publish(transport::kPlantTruth, out.truth);
    published_utime[k % kRing] = out.position.header.publish_utime;
    if (k == last_tick) break;

    node.drain();
    if (!latest || latest->header.tick <= used_tick) ++missing;
    const int64_t age = latest ? k - latest->header.tick : k + 1;
    if (latest && age <= max_age) {
      tau = transport::toEigen(latest->tau_applied);
      applied = {latest->header.tick, lagrange::plant_truth_t::TORQUE_COMMANDED};
      if (latest->header.tick > used_tick)
        ages.add(static_cast<double>(transport::nowUtime() - latest->header.publish_utime) * 1e-6);
      used_tick = latest->header.tick;
    } else if (latest && age <= hold_limit) {
      // Policy "hold": the newest torque, late, its final step held flat. Never
      // an older one: under network delay the newest torque is often a few
      // periods past max_torque_age, and holding the last fresh one instead
      // would keep the arm on a torque that gets older every period.
      ++held;
      tau.rowwise() = transport::toEigen(latest->tau_applied).row(torque_steps - 1);
      applied = {latest->header.tick, lagrange::plant_truth_t::TORQUE_HELD};
    } else {
      if (k > 0) ++zeroed;  // nothing can have answered before the first sample
      tau.setZero();
      applied = {};
    }
    sim.stepProfile(tau, s.substepsPerTick());

    if (transport::monotonicNs() >= next_status) {
      status.setLoopStats(stats());
      status.publish(State::kRunning, k, t);
      next_status += 500'000'000LL;
    }
  }
  status.setLoopStats(stats());
  if (runtime::stopRequested()) {
    status.publish(State::kInterrupted, used_tick, static_cast<double>(used_tick) * s.tickPeriod());
    return 0;
  }
  if (held + zeroed > 0)
    spdlog::warn(fmt::format("stale torque: held {} periods, zeroed {} periods", held, zeroed));
  status.publish(State::kFinished, last_tick, static_cast<double>(last_tick) * s.tickPeriod(), std::nan(""),
                 "torque_held=" + std::to_string(held) + " torque_zeroed=" + std::to_string(zeroed));
  return 0;
}

}  // namespace lagrange::plant
