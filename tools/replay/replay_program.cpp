#include "tools/replay/replay_program.hpp"

#include <stdlib.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "config/scenario_json.hpp"
#include "runtime/key_file.hpp"
#include "tools/replay/replay.hpp"
#include "tools/replay/shell_words.hpp"
#include "transport/run_clock.hpp"
#include "util/output_file.hpp"
#include "wiring/netns.hpp"

namespace lagrange::tools {

ScratchDirectory::ScratchDirectory(std::string output_name) : output_name_(std::move(output_name)) {
  const std::filesystem::path temp = std::filesystem::temp_directory_path();
  std::string pattern = (temp / "lagrange-replay-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr)
    throw ReplayError("cannot create a private directory for the replay's key and the program's output in " +
                          temp.string() + ": " + std::strerror(errno),
                      {}, ErrorKind::kRuntimeFault);
  path_ = pattern;
}

ScratchDirectory::~ScratchDirectory() {
  std::error_code ignored;
  std::filesystem::remove(keyFile(), ignored);
  std::filesystem::remove(configFile(), ignored);
  std::filesystem::remove(configJsonFile(), ignored);
  if (!keep_output_) std::filesystem::remove_all(path_, ignored);
}

ReplayedProgram::ReplayedProgram(const config::Scenario& s, const std::string& role,
                                 const std::vector<std::string>& command)
    : role_(role), scratch_(role + ".log") {
  if (!wiring::insidePrivateNetns())
    throw ReplayError("replaying an external " + role +
                      " runs it on a bus of its own, in a private network namespace; lagrange replay "
                      "enters one itself (it needs util-linux's unshare)");
  try {
    wiring::configureLoopbackMulticast();
  } catch (const std::exception& e) {
    throw ReplayError("cannot set up the private network for the external " + role + ": " + e.what(), {},
                      ErrorKind::kRuntimeFault);
  }
  url_ = wiring::freshLcmUrl();
  run_id_ = wiring::randomRunId();
  // The program gets a key of this bus, as in a run: it signs what it
  // publishes and checks what it receives (docs/external_programs.md).
  key_ = transport::randomMessageKey();
  runtime::writeKeyFile(scratch_.keyFile(), key_);
  // Its output: created here, private (0600) and never through a link, then
  // appended to by the child.
  util::writeOutputFile(scratch_.outputFile(), "", 0600);
  // The environment a run gives it (tools/run/run_command.cpp), the log's
  // resolved scenario among it (in lockstep): a program that reads its
  // parameters from the scenario replays as it ran.
  config::Scenario lockstep = s;
  lockstep.mode = config::Mode::kLockstep;
  util::writeOutputFile(scratch_.configFile(), config::toYaml(lockstep), 0600);
  util::writeOutputFile(scratch_.configJsonFile(), config::toJson(lockstep), 0600);
  wiring::ChildSpec spec;
  spec.name = role;
  spec.argv = command;  // the user's, never the log's; it starts where the user is
  spec.log_path = scratch_.outputFile();
  spec.append_log = true;
  spec.env = {
      "LAGRANGE_LCM_URL=" + url_,
      "LAGRANGE_RUN_ID=" + std::to_string(run_id_),
      "LAGRANGE_KEY_FILE=" + scratch_.keyFile(),
      "LAGRANGE_CONFIG=" + scratch_.configFile(),
      "LAGRANGE_CONFIG_JSON=" + scratch_.configJsonFile(),
      "LAGRANGE_JOINTS=" + std::to_string(s.dof()),
      "LAGRANGE_MODE=lockstep",
      std::string(transport::kClockOffsetVariable) + "=" + std::to_string(transport::clockOffsetUs())};
  std::printf(
      "lagrange replay: starting %s with a run's environment: LAGRANGE_LCM_URL, LAGRANGE_RUN_ID, "
      "LAGRANGE_KEY_FILE (a key of this replay), LAGRANGE_CONFIG and LAGRANGE_CONFIG_JSON (the log's "
      "scenario%s), LAGRANGE_JOINTS=%d, LAGRANGE_MODE=lockstep, LAGRANGE_CLOCK_OFFSET_US\n",
      shellWords(command).c_str(), s.mode == config::Mode::kLockstep ? "" : ", mode lockstep", s.dof());
  std::fflush(stdout);  // before the fork: the child must not inherit the line unwritten
  supervisor_.start(spec);
}

std::unique_ptr<transport::LcmNode> ReplayedProgram::node(const std::string& process) const {
  auto node = std::make_unique<transport::LcmNode>(process, url_, run_id_);
  node->authenticate(key_);
  return node;
}

void ReplayedProgram::requireRunning(long long done, size_t of, const std::string& outputs) {
  for (const wiring::ChildExit& e : supervisor_.reap())
    throw ReplayError("the external " + role_ + " " + e.describe() + " after " + std::to_string(done) +
                          " of " + std::to_string(of) + " " + outputs +
                          " (its output: " + scratch_.keepOutput() + ")",
                      {}, ErrorKind::kRuntimeFault);
}

void ReplayedProgram::silent(const std::string& what) {
  throw ReplayError("the external " + role_ + " did not " + what +
                        " within 10 s (its output: " + scratch_.keepOutput() + ")",
                    {}, ErrorKind::kRuntimeFault);
}

void ReplayedProgram::finish() {
  supervisor_.waitAll(2.0);
  supervisor_.stopAll(2.0);
}

}  // namespace lagrange::tools
