#include "tools/replay/replay_external.hpp"

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <optional>

#include "lagrange/control_command_t.hpp"
#include "logs/log_reader.hpp"
#include "runtime/status_reporter.hpp"
#include "tools/replay/replay_gaps.hpp"
#include "tools/replay/replay_program.hpp"
#include "tools/replay/shell_words.hpp"
#include "transport/channels.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"

namespace lagrange::tools {

namespace {

using Clock = std::chrono::steady_clock;

// The answer as the replay compares it: the command's fields as a core's output.
controller::Theorem1Output asOutput(const lagrange::control_command_t& m) {
  controller::Theorem1Output out;
  out.u = transport::toEigen(m.u);
  out.q_desired = transport::toEigen(m.q_desired);
  out.q_error = transport::toEigen(m.q_error);
  out.theta = transport::toEigen(m.theta);
  out.filter_state = transport::toEigen(m.filter_state);
  out.xi_error = m.xi_error.empty() ? Eigen::MatrixXd(0, m.num_joints) : transport::toEigen(m.xi_error);
  return out;
}

}  // namespace

LoggedController loggedController(const std::string& log_path, const std::string& section) {
  LoggedController logged;
  try {
    logs::LogEventReader log(log_path);
    for (int i = 0; i < 16; ++i) {
      const lcm::LogEvent* ev = log.next();
      if (ev == nullptr) return logged;
      if (ev->channel != transport::kScenario) continue;
      const std::optional<std::string> yaml = logs::scenarioYaml(*ev);
      if (!yaml) return logged;
      const YAML::Node program = YAML::Load(*yaml)[section];
      if (!program || !program.IsMap()) return logged;
      // A plant section without a type is the simulated plant's.
      if (!program["type"] && section == "plant") logged.type = "simulated";
      if (!program["type"] || !program["type"].IsScalar()) return logged;
      logged.type = program["type"].as<std::string>();
      if (logged.type != "external") return logged;
      const YAML::Node command = program["command"];
      if (command && command.IsSequence())
        for (const YAML::Node& word : command)
          logged.command.push_back(word.IsScalar() ? word.as<std::string>() : YAML::Dump(word));
      return logged;
    }
  } catch (const logs::LogError&) {
    return logged;  // openLog names what is wrong with the log
  } catch (const YAML::Exception&) {
    return logged;  // and with its scenario
  }
  return logged;
}

void replayExternalController(const replay_log::Opened& o, ReplayResult& result,
                              const std::vector<std::string>& command) {
  const config::Scenario& s = o.scenario;
  if (command.empty())
    throw ReplayError(
        "the log's controller is external, and replay runs no program a log names: its "
        "command is " +
        shellWords(s.controller.command) +
        "; to replay it, name the program yourself after -- (lagrange replay LOG -- "
        "COMMAND ARGS...)");
  ReplayedProgram program(s, "controller", command);
  const std::unique_ptr<transport::LcmNode> node = program.node("plant");
  std::optional<lagrange::control_command_t> answer;
  node->subscribe<lagrange::control_command_t>(
      transport::kControlCommand, [&](const auto& m) { return transport::validate(m, s.dof()); },
      [&](const lagrange::control_command_t& m) { answer = m; });

  // As the lockstep plant: each position until its answer comes, re-sent
  // every 50 ms; a controller silent for 10 s (or gone) ends the replay.
  const replay_log::OutputSequence sequence =
      replay_log::outputSequence(transport::kControlCommand, o.logged_mode);
  const lagrange::header_t* previous = nullptr;
  for (const lagrange::control_command_t& recorded : o.rec.commands) {
    replay_log::requireNoGap(o.rec, transport::kControlCommand, sequence, previous, recorded.header,
                             result.commands);
    previous = &recorded.header;
    replay_log::fitting(o, recorded, transport::kControlCommand);
    const int64_t k = recorded.input_position_tick;
    const lagrange::plant_position_t& position = replay_log::input(
        o, o.rec.positions, k, transport::kPlantPosition, transport::kControlCommand, recorded.header.tick);
    replay_log::requireTaken(static_cast<Eigen::Index>(position.q.size()), 1, s.dof(), 1,
                             "PLANT_POSITION tick " + std::to_string(k) + "'s q");
    answer.reset();
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    auto resend = Clock::now();
    while (!(answer && answer->input_position_tick == k)) {
      if (Clock::now() >= resend) {
        node->publish(transport::kPlantPosition, position);
        resend = Clock::now() + std::chrono::milliseconds(50);
      }
      program.requireRunning(result.commands, o.rec.commands.size(), "commands");
      if (Clock::now() > deadline) program.silent("answer PLANT_POSITION tick " + std::to_string(k));
      node->handle(5);
    }
    ++result.commands;
    const std::string d = replay_log::commandDifference(recorded, asOutput(*answer));
    if (!d.empty()) {
      result.divergence = replay_log::at(k, position.header.sim_time) + transport::kControlCommand + "." + d;
      break;
    }
  }
  runtime::StatusReporter status(*node);
  for (int copy = 0; copy < 3; ++copy) status.publish(transport::ProcessState::kFinished, 0, 0.0);
  program.finish();
}

}  // namespace lagrange::tools
