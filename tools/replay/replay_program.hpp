#pragma once
/// @file
/// What replaying a program from outside (an external controller or plant,
/// docs/external_programs.md) needs around it: a private folder for the
/// replay's key, the log's scenario and the program's output, the bus of its
/// own, and the environment a run gives such a program.

#include <memory>
#include <string>
#include <vector>

#include "config/scenario.hpp"
#include "transport/lcm_node.hpp"
#include "transport/message_auth.hpp"
#include "wiring/supervisor.hpp"

namespace lagrange::tools {

/// A directory only this user can enter (mkdtemp: mode 0700, a name nobody
/// can guess or plant beforehand) for the replay's key and the program's
/// output. Both go with the replay, but the output stays when the program
/// failed, so that its messages can be read.
class ScratchDirectory {
 public:
  /// `output_name`: the program's output file in it ("controller.log").
  explicit ScratchDirectory(std::string output_name);
  ~ScratchDirectory();
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  std::string keyFile() const { return path_ + "/run.key"; }
  std::string configFile() const { return path_ + "/config.resolved.yaml"; }
  std::string configJsonFile() const { return path_ + "/config.resolved.json"; }
  std::string outputFile() const { return path_ + "/" + output_name_; }
  /// The program failed: its output stays, and the error names it; else all goes.
  std::string keepOutput() {
    keep_output_ = true;
    return outputFile();
  }

 private:
  std::string path_, output_name_;
  bool keep_output_ = false;
};

/// The replay's bus and the program on it, started as `role` ("controller",
/// "plant") with the environment a run gives it (tools/run/run_command.cpp):
/// the LCM URL of a fresh bus in this private network namespace, a fresh
/// run id and key, the scenario `s` (the log's, in lockstep) as YAML and
/// JSON, the joints, LAGRANGE_MODE=lockstep and the clock offset. Prints one
/// line naming what it gave. @throws ReplayError outside a private network
/// namespace, or when it cannot be set up.
class ReplayedProgram {
 public:
  ReplayedProgram(const config::Scenario& s, const std::string& role,
                  const std::vector<std::string>& command);
  ReplayedProgram(const ReplayedProgram&) = delete;
  ReplayedProgram& operator=(const ReplayedProgram&) = delete;

  /// A node on the program's bus, publishing as `process`, with the replay's key.
  std::unique_ptr<transport::LcmNode> node(const std::string& process) const;
  /// Throws ReplayError (a runtime fault) when the program has ended:
  /// "the external ROLE exited ... after N of M OUTPUTS (its output: FILE)".
  void requireRunning(long long done, size_t of, const std::string& outputs);
  /// Throws ReplayError (a runtime fault): the program did not answer `what` within 10 s.
  [[noreturn]] void silent(const std::string& what);
  /// Ends the program: a grace to end on its own, then a stop.
  void finish();

 private:
  std::string role_;
  ScratchDirectory scratch_;
  std::string url_;
  int64_t run_id_ = 0;
  transport::MessageKey key_{};
  wiring::Supervisor supervisor_;
};

}  // namespace lagrange::tools
