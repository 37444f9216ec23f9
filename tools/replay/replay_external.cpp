#include "tools/replay/replay_external.hpp"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>

#include "lagrange/control_command_t.hpp"
#include "logs/log_reader.hpp"
#include "runtime/key_file.hpp"
#include "runtime/status_reporter.hpp"
#include "transport/channels.hpp"
#include "transport/lcm_node.hpp"
#include "transport/messages.hpp"
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

bool isExternalControllerLog(const std::string& log_path) {
  try {
    logs::LogEventReader log(log_path);
    for (int i = 0; i < 16; ++i) {
      const lcm::LogEvent* ev = log.next();
      if (ev == nullptr) return false;
      if (ev->channel != transport::kScenario) continue;
      const std::optional<std::string> yaml = logs::scenarioYaml(*ev);
      if (!yaml) return false;
      const YAML::Node controller = YAML::Load(*yaml)["controller"];
      return controller && controller["type"] && controller["type"].as<std::string>() == "external";
    }
  } catch (const logs::LogError&) {
    return false;  // openLog names what is wrong with the log
  } catch (const YAML::Exception&) {
    return false;  // and with its scenario
  }
  return false;
}

void replayExternalController(const replay_log::Opened& o, ReplayResult& result) {
  const config::Scenario& s = o.scenario;
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
  std::random_device rd;
  const int64_t run_id = ((static_cast<int64_t>(rd()) << 20) ^ rd()) | 1;  // never 0: 0 accepts any run
  transport::LcmNode node("plant", url, run_id);
  // The program gets a key of this bus, as in a run: it signs its commands
  // and checks the positions (docs/external_controllers.md).
  std::string key_dir = (std::filesystem::temp_directory_path() / "lagrange-replay-key-XXXXXX").string();
  if (mkdtemp(key_dir.data()) == nullptr)
    throw ReplayError("cannot create a private directory for the replay's key in " +
                          std::filesystem::temp_directory_path().string() + ": " + std::strerror(errno),
                      {}, ErrorKind::kRuntimeFault);
  const std::string key_file = key_dir + "/run.key";
  const transport::MessageKey key = transport::randomMessageKey();
  runtime::writeKeyFile(key_file, key);
  node.authenticate(key);
  struct RemoveKey {
    std::string dir;
    ~RemoveKey() { std::filesystem::remove_all(dir); }
  } remove_key{key_dir};
  std::optional<lagrange::control_command_t> answer;
  node.subscribe<lagrange::control_command_t>(
      transport::kControlCommand, [&](const auto& m) { return transport::validate(m, s.dof()); },
      [&](const lagrange::control_command_t& m) { answer = m; });

  const std::string log = (std::filesystem::temp_directory_path() /
                           ("lagrange-replay-external-" + std::to_string(getpid()) + ".log"))
                              .string();
  wiring::Supervisor supervisor;
  wiring::ChildSpec spec;
  spec.name = "controller";
  spec.argv = s.controller.command;
  spec.working_directory = s.controller.working_directory;
  spec.log_path = log;
  spec.env = {"LAGRANGE_LCM_URL=" + url, "LAGRANGE_RUN_ID=" + std::to_string(run_id),
              "LAGRANGE_KEY_FILE=" + key_file, "LAGRANGE_JOINTS=" + std::to_string(s.dof()),
              "LAGRANGE_MODE=lockstep"};
  supervisor.start(spec);

  // As the lockstep plant: each position until its answer comes, re-sent
  // every 50 ms; a controller silent for 10 s (or gone) ends the replay.
  for (const lagrange::control_command_t& recorded : o.rec.commands) {
    const int64_t k = recorded.input_position_tick;
    const lagrange::plant_position_t& position = replay_log::input(
        o.rec.positions, k, transport::kPlantPosition, transport::kControlCommand, recorded.header.tick);
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
                              std::to_string(o.rec.commands.size()) + " commands (its output: " + log + ")",
                          {}, ErrorKind::kRuntimeFault);
      if (Clock::now() > deadline)
        throw ReplayError("the external controller did not answer PLANT_POSITION tick " + std::to_string(k) +
                              " within 10 s (its output: " + log + ")",
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
  std::filesystem::remove(log);
}

}  // namespace lagrange::tools
