/// @file
/// `lagrange check-gains` (tools/check_gains/check_gains.hpp).
#include "tools/check_gains/check_gains.hpp"

#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "controller/gain_suggestion.hpp"
#include "model/reference.hpp"
#include "tools/command_error.hpp"
#include "util/error.hpp"
#include "util/terminal_text.hpp"
#include "wiring/sampled_simulation.hpp"

namespace lagrange::tools {

namespace {

std::string hz(double rate) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g Hz", rate);
  return buf;
}

// --suggest's last line: it stops at the first gains its rules give that pass;
// lagrange tune searches for the fastest that pass (#55).
void nameTune(const std::string& config_path) {
  std::cout << "\nfor the gains that converge fastest and pass the same checks (eq. (12) kept with "
               "--require-condition): lagrange tune "
            << util::terminalSafe(config_path) << " --out DIR (docs/tuning.md)\n";
}

// --suggest: the search (controller/gain_suggestion.hpp), then the full
// check of what it found, the simulation included; exit 0 only when that
// passes at the configured rate.
int suggestGains(const config::Scenario& s, bool simulate) {
  const std::string at = hz(s.plant.publish_rate);
  controller::GainSearch search;
  try {
    search = controller::searchGains(s);
  } catch (const std::range_error& e) {
    std::cout << "\nno suggestion: " << util::terminalSafeLines(e.what()) << "\n";
    return kExitFailed;
  }
  if (!search.tried.empty()) {
    std::cout << "\n--suggest: candidates linearised at " << at << ":";
    for (const std::string& line : search.tried) std::cout << "\n  " << util::terminalSafe(line);
    std::cout << "\n";
  }
  if (!search.suggested) {
    std::cout << "\nno suggestion: found no gains that pass the checks at " << at
              << ". What binds: " << util::terminalSafeLines(search.binding) << "\n";
    return kExitFailed;
  }
  controller::GainReport check = controller::checkGains(*search.suggested);
  if (simulate) check.simulated = wiring::simulateSampledData(*search.suggested);
  // The linearised check may be "not assessed" on a plant with damping or
  // friction: the search linearised the nominal plant, the simulation judges this one.
  const bool passes =
      check.holds() && check.sampled.verdict != "unstable" && !(check.simulated && check.simulated->fails());
  if (!passes) {
    std::cout
        << "\nno suggestion: the best candidate (the paper's gain conditions and the linearised check at "
        << at << " pass) fails the full check:\n"
        << util::terminalSafeLines(controller::describe(check)) << "\nWhat binds: "
        << (check.simulated && check.simulated->fails()
                ? std::string("the sampled loop simulated as configured") +
                      (s.actuator.saturation ? ", torque limits (actuator.saturation) included," : "") +
                      " is " + check.simulated->verdict + " with these gains"
                : std::string("the conditions above"))
        << "\n";
    return kExitFailed;
  }
  std::cout << "\nsuggested gains (pass eq. (12) or the chain's conditions, and the sampled-data checks at "
            << at << "; other keys unchanged):\n"
            << util::terminalSafeLines(controller::controllerYaml(*search.suggested)) << "\nwith them:\n"
            << util::terminalSafeLines(controller::describe(check)) << "\n";
  return 0;
}

}  // namespace

int checkGainsCommand(const std::string& config_path, const std::vector<std::string>& overrides,
                      bool suggest_gains, bool simulate) {
  try {
    const config::Scenario s = config::loadScenario(config_path, overrides);
    // Held while the checks run: a free_motion reference is then integrated
    // once for the report, the simulations and the suggestion (model/reference.hpp).
    const model::Reference reference(s.reference);
    controller::GainReport r = controller::checkGains(s);
    // With --suggest the simulation is the suggestion's (seconds each): the
    // configured gains get the conditions and the linearised check.
    if (simulate && !suggest_gains) r.simulated = wiring::simulateSampledData(s);
    std::cout << util::terminalSafeLines(controller::describe(r)) << "\n";  // joint names from a URDF
    // Exit 1 when the theory's conditions fail, or when the sampled loop at the
    // configured rate is unstable about the reference or diverges in
    // simulation, or is unstable in the linearised check ("slow" and
    // "offset" only warn).
    if (!suggest_gains)
      return r.holds() && r.sampled.verdict != "unstable" && !(r.simulated && r.simulated->fails()) ? 0 : 1;
    if (r.unchecked) {
      std::cout << "\nno suggestion: --suggest knows the paper's controllers only\n";
      nameTune(config_path);
      return kExitFailed;
    }
    const int exit_code = suggestGains(s, simulate);
    nameTune(config_path);
    return exit_code;
  } catch (const config::ConfigError& e) {
    return failWith("lagrange check-gains", e);
  } catch (const std::exception& e) {
    return failWith("lagrange check-gains: cannot evaluate the gain conditions", e);
  }
}

}  // namespace lagrange::tools
