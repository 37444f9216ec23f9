#include "tools/replay/replay_external.hpp"

#include <stdlib.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>

#include "config/scenario_json.hpp"
#include "lagrange/control_command_t.hpp"
#include "logs/log_reader.hpp"
#include "runtime/key_file.hpp"
#include "runtime/status_reporter.hpp"
#include "tools/replay/replay_gaps.hpp"
#include "tools/replay/shell_words.hpp"
#include "transport/channels.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"
#include "transport/run_clock.hpp"
#include "util/output_file.hpp"
#include "wiring/netns.hpp"
#include "wiring/supervisor.hpp"

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

LoggedController loggedController(const std::string& log_path) {
  LoggedController logged;
  try {
    logs::LogEventReader log(log_path);
    for (int i = 0; i < 16; ++i) {
      const lcm::LogEvent* ev = log.next();
      if (ev == nullptr) return logged;
      if (ev->channel != transport::kScenario) continue;
      const std::optional<std::string> yaml = logs::scenarioYaml(*ev);
      if (!yaml) return logged;
      const YAML::Node controller = YAML::Load(*yaml)["controller"];
      if (!controller || !controller.IsMap() || !controller["type"] || !controller["type"].IsScalar())
        return logged;
      logged.type = controller["type"].as<std::string>();
      if (logged.type != "external") return logged;
      const YAML::Node command = controller["command"];
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

namespace {

// A directory only this user can enter (mkdtemp: mode 0700, a name nobody
// can guess or plant beforehand) for the replay's key and the program's
// output. Both go with the replay, but the output stays when the program
// failed, so that its messages can be read.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    const std::filesystem::path temp = std::filesystem::temp_directory_path();
    std::string pattern = (temp / "lagrange-replay-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr)
      throw ReplayError(
          "cannot create a private directory for the replay's key and the controller's output in " +
              temp.string() + ": " + std::strerror(errno),
          {}, ErrorKind::kRuntimeFault);
    path_ = pattern;
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove(keyFile(), ignored);
    std::filesystem::remove(configFile(), ignored);
    std::filesystem::remove(configJsonFile(), ignored);
    if (!keep_output_) std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  std::string keyFile() const { return path_ + "/run.key"; }
  std::string configFile() const { return path_ + "/config.resolved.yaml"; }
  std::string configJsonFile() const { return path_ + "/config.resolved.json"; }
  std::string outputFile() const { return path_ + "/controller.log"; }
  /// The program failed: its output stays, and the error names it; else all goes.
  std::string keepOutput() {
    keep_output_ = true;
    return outputFile();
  }

 private:
  std::string path_;
  bool keep_output_ = false;
};

}  // namespace

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
  if (!wiring::insidePrivateNetns())
    throw ReplayError(
        "replaying an external controller runs it on a bus of its own, in a private network "
        "namespace; lagrange replay enters one itself (it needs util-linux's unshare)");
  try {
    wiring::configureLoopbackMulticast();
  } catch (const std::exception& e) {
    throw ReplayError(
        std::string("cannot set up the private network for the external controller: ") + e.what(), {},
        ErrorKind::kRuntimeFault);
  }
  const std::string url = wiring::freshLcmUrl();
  const int64_t run_id = wiring::randomRunId();
  transport::LcmNode node("plant", url, run_id);
  // The program gets a key of this bus, as in a run: it signs its commands
  // and checks the positions (docs/external_programs.md).
  ScratchDirectory scratch;
  const transport::MessageKey key = transport::randomMessageKey();
  runtime::writeKeyFile(scratch.keyFile(), key);
  node.authenticate(key);
  std::optional<lagrange::control_command_t> answer;
  node.subscribe<lagrange::control_command_t>(
      transport::kControlCommand, [&](const auto& m) { return transport::validate(m, s.dof()); },
      [&](const lagrange::control_command_t& m) { answer = m; });

  // Its output: created here, private (0600) and never through a link, then
  // appended to by the child.
  const std::string output = scratch.outputFile();
  util::writeOutputFile(output, "", 0600);
  wiring::Supervisor supervisor;
  wiring::ChildSpec spec;
  spec.name = "controller";
  spec.argv = command;  // the user's, never the log's; it starts where the user is
  spec.log_path = output;
  spec.append_log = true;
  // The environment a run gives it (tools/run/run_command.cpp), the log's
  // resolved scenario among it: a program that reads its parameters from the
  // scenario replays as it ran.
  util::writeOutputFile(scratch.configFile(), config::toYaml(s), 0600);
  util::writeOutputFile(scratch.configJsonFile(), config::toJson(s), 0600);
  spec.env = {
      "LAGRANGE_LCM_URL=" + url,
      "LAGRANGE_RUN_ID=" + std::to_string(run_id),
      "LAGRANGE_KEY_FILE=" + scratch.keyFile(),
      "LAGRANGE_CONFIG=" + scratch.configFile(),
      "LAGRANGE_CONFIG_JSON=" + scratch.configJsonFile(),
      "LAGRANGE_JOINTS=" + std::to_string(s.dof()),
      "LAGRANGE_MODE=lockstep",
      std::string(transport::kClockOffsetVariable) + "=" + std::to_string(transport::clockOffsetUs())};
  std::printf(
      "lagrange replay: starting %s with a run's environment: LAGRANGE_LCM_URL, LAGRANGE_RUN_ID, "
      "LAGRANGE_KEY_FILE (a key of this replay), LAGRANGE_CONFIG and LAGRANGE_CONFIG_JSON (the log's "
      "scenario), LAGRANGE_JOINTS=%d, LAGRANGE_MODE=lockstep, LAGRANGE_CLOCK_OFFSET_US\n",
      shellWords(command).c_str(), s.dof());
  std::fflush(stdout);  // before the fork: the child must not inherit the line unwritten
  supervisor.start(spec);

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
        node.publish(transport::kPlantPosition, position);
        resend = Clock::now() + std::chrono::milliseconds(50);
      }
      for (const wiring::ChildExit& e : supervisor.reap())
        throw ReplayError("the external controller " + e.describe() + " after " +
                              std::to_string(result.commands) + " of " +
                              std::to_string(o.rec.commands.size()) +
                              " commands (its output: " + scratch.keepOutput() + ")",
                          {}, ErrorKind::kRuntimeFault);
      if (Clock::now() > deadline)
        throw ReplayError("the external controller did not answer PLANT_POSITION tick " + std::to_string(k) +
                              " within 10 s (its output: " + scratch.keepOutput() + ")",
                          {}, ErrorKind::kRuntimeFault);
      node.handle(5);
    }
    ++result.commands;
    const std::string d = replay_log::commandDifference(recorded, asOutput(*answer));
    if (!d.empty()) {
      result.divergence = replay_log::at(k, position.header.sim_time) + transport::kControlCommand + "." + d;
      break;
    }
  }
  runtime::StatusReporter status(node);
  for (int copy = 0; copy < 3; ++copy) status.publish(transport::ProcessState::kFinished, 0, 0.0);
  supervisor.waitAll(2.0);
  supervisor.stopAll(2.0);
}

}  // namespace lagrange::tools
