/// @file
/// `lagrange replay --component plant -- COMMAND` of a log whose plant is a
/// program from outside (tools/replay/replay_external.hpp).

#include <chrono>
#include <map>

#include "lagrange/actuator_state_t.hpp"
#include "runtime/status_reporter.hpp"
#include "tools/replay/replay_external.hpp"
#include "tools/replay/replay_gaps.hpp"
#include "tools/replay/replay_program.hpp"
#include "tools/replay/shell_words.hpp"
#include "transport/channels.hpp"
#include "transport/messages.hpp"

namespace lagrange::tools {

namespace {

using Clock = std::chrono::steady_clock;
using namespace replay_log;

// The answer to tick k, as the actuator would send it: the torque applied
// over the period after k, one step.
lagrange::actuator_state_t answerOf(int64_t k, double t, const Eigen::VectorXd& tau) {
  lagrange::actuator_state_t a{};
  a.header = transport::makeHeader(k, t);
  a.input_command_tick = k;
  a.num_joints = static_cast<int32_t>(tau.size());
  a.order = 0;
  a.u_commanded = transport::toStd(tau);
  a.torque_steps = 1;
  a.tau_applied = {a.u_commanded};
  a.saturated.assign(static_cast<size_t>(tau.size()), 0);
  return a;
}

// First difference between the recorded sample of a tick and the program's.
std::string firstDifference(const Opened& o, const lagrange::plant_truth_t& recorded,
                            const lagrange::plant_truth_t& truth,
                            const lagrange::plant_position_t& position) {
  std::string d = compare("PLANT_TRUTH.sim_time", recorded.header.sim_time, truth.header.sim_time);
  if (d.empty()) d = compare("PLANT_TRUTH.q", recorded.q, transport::toEigen(truth.q));
  if (d.empty()) d = compare("PLANT_TRUTH.qdot", recorded.qdot, transport::toEigen(truth.qdot));
  if (d.empty())
    d = compare("PLANT_TRUTH.tau_applied", recorded.tau_applied, transport::toEigen(truth.tau_applied));
  if (d.empty()) d = compare("PLANT_TRUTH.kinetic_energy", recorded.kinetic_energy, truth.kinetic_energy);
  if (d.empty())
    d = compare("PLANT_TRUTH.potential_energy", recorded.potential_energy, truth.potential_energy);
  if (d.empty()) d = compare("PLANT_TRUTH.total_energy", recorded.total_energy, truth.total_energy);
  // Which answer a realtime plant applied is the live loop's; a lockstep one always the tick's.
  if (d.empty() && o.logged_mode == config::Mode::kLockstep) {
    if (recorded.input_actuator_tick != truth.input_actuator_tick)
      d = "PLANT_TRUTH.input_actuator_tick: recorded " + std::to_string(recorded.input_actuator_tick) +
          ", replayed " + std::to_string(truth.input_actuator_tick);
    else if (recorded.torque_source != truth.torque_source)
      d = "PLANT_TRUTH.torque_source: recorded " + std::to_string(recorded.torque_source) + ", replayed " +
          std::to_string(truth.torque_source);
  }
  const auto it = o.rec.positions.find(recorded.header.tick);
  if (d.empty() && it != o.rec.positions.end())
    d = compare("PLANT_POSITION.q", fitting(o, it->second, transport::kPlantPosition).q,
                transport::toEigen(position.q));
  return d;
}

}  // namespace

void replayExternalPlant(const Opened& o, ReplayResult& result, const std::vector<std::string>& command) {
  const config::Scenario& s = o.scenario;
  if (command.empty())
    throw ReplayError("the log's plant is external, and replay runs no program a log names: its command is " +
                      shellWords(s.plant.command) +
                      "; to replay it, name the program yourself after -- (lagrange replay LOG --component "
                      "plant -- COMMAND ARGS...)");
  if (s.torqueStepsPerTick() != 1)
    throw ReplayError("the replayed scenario has actuator.rate " + std::to_string(s.actuator.rate) +
                      " Hz; an external plant takes one torque per period (plant.publish_rate)");
  ReplayedProgram program(s, "plant", command);
  // The replay is the actuator (the answers) and the logger (the window).
  const std::unique_ptr<transport::LcmNode> actuator = program.node("actuator");
  const std::unique_ptr<transport::LcmNode> logger = program.node("logger");
  const int n = s.dof();
  std::map<int64_t, lagrange::plant_truth_t> truths;
  std::map<int64_t, lagrange::plant_position_t> positions;
  bool finished = false;
  logger->subscribe<lagrange::plant_truth_t>(
      transport::kPlantTruth, [n](const auto& m) { return transport::validate(m, n); },
      [&](const lagrange::plant_truth_t& m) { truths.emplace(m.header.tick, m); });
  logger->subscribe<lagrange::plant_position_t>(
      transport::kPlantPosition, [n](const auto& m) { return transport::validate(m, n); },
      [&](const lagrange::plant_position_t& m) { positions.emplace(m.header.tick, m); });
  logger->subscribe<lagrange::status_t>(
      transport::kStatus, [](const auto& m) { return transport::validate(m); },
      [&](const lagrange::status_t& m) {
        if (m.process == "plant" && m.state == transport::toString(transport::ProcessState::kFinished))
          finished = true;
      });
  runtime::StatusReporter window(*logger);
  Eigen::MatrixXd tau = Eigen::MatrixXd::Zero(1, n);

  // Until `ready` holds: the logger's word that every tick before `confirmed`
  // is in, and the answer to the previous tick, every 50 ms; 10 s at most.
  auto serve = [&](int64_t confirmed, const lagrange::actuator_state_t* answer, const std::string& awaited,
                   const auto& ready) {
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    auto resend = Clock::now();
    while (!ready()) {
      if (Clock::now() >= resend) {
        window.publish(transport::ProcessState::kRunning, confirmed, 0.0);
        if (answer != nullptr) actuator->publish(transport::kActuatorState, *answer);
        resend = Clock::now() + std::chrono::milliseconds(50);
      }
      program.requireRunning(result.commands, o.rec.truths.size(), "samples");
      if (Clock::now() > deadline) program.silent(awaited);
      logger->handle(5);
    }
  };

  const lagrange::header_t* previous = nullptr;
  std::optional<lagrange::actuator_state_t> answer;
  int64_t last = -1;
  for (const lagrange::plant_truth_t& recorded : o.rec.truths) {  // in tick order (openLog)
    requireNoGap(o.rec, transport::kPlantTruth, OutputSequence::kEveryTick, previous, recorded.header,
                 result.commands);
    previous = &recorded.header;
    fitting(o, recorded, transport::kPlantTruth);
    const int64_t k = recorded.header.tick;
    if (k > 0) {  // the torque the log says was applied over the period ending at k answers tick k-1
      chooseTorque(o, recorded, tau);
      answer = answerOf(k - 1, static_cast<double>(k - 1) * s.tickPeriod(), tau.row(0).transpose());
    }
    serve(k - 1, answer ? &*answer : nullptr,
          "publish PLANT_TRUTH and PLANT_POSITION of tick " + std::to_string(k),
          [&] { return truths.count(k) != 0 && positions.count(k) != 0; });
    ++result.commands;
    last = k;
    const std::string d = firstDifference(o, recorded, truths.at(k), positions.at(k));
    if (!d.empty()) {
      result.divergence = at(k, recorded.header.sim_time) + d;
      break;
    }
  }
  // The program awaits an answer to the last tick too, and the logger's word
  // on every tick, before it finishes; its end is not compared.
  if (!result.divergence && last >= 0 && last == s.lastTick()) {
    const lagrange::actuator_state_t end =
        answerOf(last, static_cast<double>(last) * s.tickPeriod(), Eigen::VectorXd::Zero(n));
    try {
      serve(last, &end, "finish after the log's last tick", [&] { return finished; });
    } catch (const ReplayError& e) {
      result.warnings.push_back(
          e.what());  // every recorded sample matched; the end is the run's, not the log's
    }
  }
  program.finish();
}

}  // namespace lagrange::tools
