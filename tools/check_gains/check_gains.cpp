/// @file
/// `lagrange check-gains` (tools/check_gains/check_gains.hpp).
#include "tools/check_gains/check_gains.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "controller/gain_suggestion.hpp"
#include "tools/command_error.hpp"
#include "util/error.hpp"

namespace lagrange::tools {

int checkGainsCommand(const std::string& config_path, const std::vector<std::string>& overrides,
                      bool suggest) {
  try {
    const config::Scenario s = config::loadScenario(config_path, overrides);
    const controller::GainReport r = controller::checkGains(s);
    std::cout << controller::describe(r) << "\n";
    // Exit 1 when the theory's conditions fail, or when the sampled loop at the
    // configured rate is unstable near the reference ("slow" only warns).
    if (!suggest) return r.holds() && r.sampled.verdict != "unstable" ? 0 : 1;
    if (r.unchecked) {
      std::cout << "\nno suggestion: --suggest knows the paper's controllers only\n";
      return kExitFailed;
    }
    config::Scenario suggested;
    try {
      suggested = controller::suggestGains(s);
    } catch (const std::range_error& e) {
      std::cout << "\nno suggestion: " << e.what() << "\n";
      return kExitFailed;
    }
    const controller::GainReport check = controller::checkGains(suggested);
    std::cout << "\nsuggested gains (the paper's constructive rules; other keys unchanged):\n"
              << controller::controllerYaml(suggested) << "\nwith them:\n"
              << controller::describe(check) << "\n";
    return check.holds() ? 0 : 1;
  } catch (const config::ConfigError& e) {
    return failWith("lagrange check-gains", e);
  } catch (const std::exception& e) {
    return failWith("lagrange check-gains: cannot evaluate the gain conditions", e);
  }
}

namespace {
struct CheckGainsOptions {
  std::string config_path;
  std::vector<std::string> overrides;
  bool suggest = false;
};
}  // namespace

Subcommand addCheckGainsCommand(CLI::App& app) {
  auto o = std::make_shared<CheckGainsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check-gains",
      "Print the gain conditions of a scenario (k_c, k_delta, eq. 11; "
      "eta and eq. 632 for m = 1; Theorem 3 and Proposition 1 "
      "for m >= 2) and whether the sampled implementation at the configured rate is adequate, "
      "without running it; exit 1 if a condition is violated or the "
      "sampled loop is unstable");
  cmd->add_option("config", o->config_path, "Scenario YAML file")->required();
  cmd->add_option("--set", o->overrides, "Override a config key: key=value; repeatable");
  cmd->add_flag("--suggest", o->suggest,
                "Also propose gains that satisfy the conditions (eq. 11; lego/632a, 794, 795 for chains) "
                "and check them; exit 0 if the suggestion passes");
  return {cmd,
          [o](const Invocation&) { return checkGainsCommand(o->config_path, o->overrides, o->suggest); }};
}

}  // namespace lagrange::tools
