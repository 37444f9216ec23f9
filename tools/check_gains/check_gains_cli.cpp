/// @file
/// `lagrange check-gains`: its command line (tools/check_gains/check_gains.hpp).
#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "tools/check_gains/check_gains.hpp"

namespace lagrange::tools {

namespace {
struct CheckGainsCommandLine {
  std::string config_path;
  std::vector<std::string> overrides;
  bool suggest = false;
  bool no_simulation = false;
};
}  // namespace

Subcommand addCheckGainsCommand(CLI::App& app) {
  auto o = std::make_shared<CheckGainsCommandLine>();
  CLI::App* cmd = app.add_subcommand("check-gains", "Check a scenario's gains and sampling rate");
  describeCommand(
      *cmd,
      "Print the gain conditions of a scenario (k_c, k_delta, eq. (12); "
      "eta and eqs. (56a)-(56c) for m = 1; Theorem 6 and Proposition 1 "
      "for m >= 2) and whether the sampled implementation at the configured rate is adequate "
      "(the loop simulated in process from the initial state and seeded states against the same loop "
      "at a fine rate, and linearised near the reference). The simulated verdict's first word: ADEQUATE, "
      "OFFSET (a steady offset the fine-rate loop shares: not sampling's doing), SLOW, UNSTABLE about the "
      "reference (maybe held off only by saturation), DIVERGES, NOT ASSESSED; the linearised one: ADEQUATE, "
      "SLOW, UNSTABLE, NOT ASSESSED (docs/sampled_data.md). Exit codes: 0 the conditions hold and neither "
      "check says UNSTABLE or DIVERGES (with --suggest: gains were found that pass all of them at the "
      "configured rate, printed as YAML); 1 a condition is violated, the sampled loop is UNSTABLE or "
      "DIVERGES "
      "(with --suggest: no gains found that pass, and the binding condition named -- the torque limits, the "
      "rate, or the reference's size through k_delta); 2 a bad scenario or option",
      {"lagrange check-gains configs/rigid_2dof.yaml"});
  cmd->add_option("config", o->config_path, "Scenario YAML file")->required();
  cmd->add_option("--set", o->overrides, "Override a config key: key=value; repeatable");
  cmd->add_flag(
      "--suggest", o->suggest,
      "Propose gains that pass every check at the configured rate: eq. (12) ((74)/(56a), (79), (80) for "
      "chains), the linearised check, the torque limits and the simulated check; or say that none "
      "was found and which condition binds (exit 1). Simulates the suggestion only");
  cmd->add_flag("--no-simulation", o->no_simulation,
                "Skip the sampled loop's simulation (seconds; tens for a flexible URDF arm): the theory's "
                "conditions and the linearised check only");
  return {cmd, [o](const Invocation&) {
            return checkGainsCommand(o->config_path, o->overrides, o->suggest, !o->no_simulation);
          }};
}

}  // namespace lagrange::tools
