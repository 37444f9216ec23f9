/// @file
/// `lagrange check-gains` (tools/check_gains/check_gains.hpp).
#include "tools/check_gains/check_gains.hpp"

#include <iostream>
#include <stdexcept>

#include "config/scenario.hpp"
#include "controller/gain_report.hpp"
#include "controller/gain_suggestion.hpp"
#include "tools/command_error.hpp"
#include "util/error.hpp"
#include "wiring/sampled_simulation.hpp"

namespace lagrange::tools {

int checkGainsCommand(const std::string& config_path, const std::vector<std::string>& overrides, bool suggest,
                      bool simulate) {
  try {
    const config::Scenario s = config::loadScenario(config_path, overrides);
    controller::GainReport r = controller::checkGains(s);
    if (simulate) r.simulated = wiring::simulateSampledData(s);
    std::cout << controller::describe(r) << "\n";
    // Exit 1 when the theory's conditions fail, or when the sampled loop at the
    // configured rate diverges in simulation, reaches the tolerance at no rate
    // tried, or is unstable near the reference ("inadequate" and "slow" only warn).
    if (!suggest)
      return r.holds() && r.sampled.verdict != "unstable" && !(r.simulated && r.simulated->fails()) ? 0 : 1;
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

}  // namespace lagrange::tools
