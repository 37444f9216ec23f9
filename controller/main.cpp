/// @file
/// The controller process: stands in for the real-time controller of a robot
/// that measures joint positions only.
///
///   PLANT_POSITION [+ ACTUATOR_STATE, PLANT_MOTOR, PLANT_RATE as the controller declares]
///     -> validate -> controller::InputAssembly -> Controller::step -> CONTROL_COMMAND
///
/// Besides PLANT_POSITION and STATUS it reads only what its needs() declare
/// (controller::subscribeDeclaredInputs); its loop is controller_loop.hpp's.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "controller/controller_loop.hpp"
#include "controller/gain_report.hpp"
#include "controller/gain_report_json.hpp"
#include "controller/registry.hpp"
#include "runtime/process.hpp"

namespace lagrange {
namespace {

int DoMain(int argc, char** argv) {
  bool strict = false;
  std::string gains_path;
  controller::GainReport gains;
  return runtime::runProcess(
      "controller", "The scenario's controller.type over LCM (Theorem 4, eq. (13); (66); (83))", argc, argv,
      {{"--strict", &strict,
        "Refuse to start when an evaluated gain condition (eq. (12); eqs. (56a)-(56c) for m = 1) is "
        "violated"},
       {"--gains", &gains_path,
        "The launcher's gain report of this scenario (OUT/gains.json), instead of checking the gains again"}},
      // The launcher prints the sampled-data check; here it would only delay the first tick.
      [&](const config::Scenario& s) {
        controller::ProcessGainReport handed = controller::processGainReport(s, gains_path);
        if (!handed.note.empty()) spdlog::warn(fmt::format("{}", handed.note));
        gains = std::move(handed.report);
      },
      [&](const config::Scenario& s, transport::LcmNode& node) {
        if (!gains.holds() && strict) {
          spdlog::error(fmt::format("{} (refusing to start: --strict)", controller::describe(gains)));
          return 3;
        }
        const char* const running = gains.holds() ? "" : " (running anyway; --strict makes this an error)";
        spdlog::log(gains.holds() ? spdlog::level::info : spdlog::level::warn, "{}{}",
                    controller::describe(gains), running);

        const std::unique_ptr<controller::Controller> ctl = controller::makeController(s);
        return controller::serveController(s, node, *ctl);
      });
}

}  // namespace
}  // namespace lagrange

int main(int argc, char** argv) { return lagrange::DoMain(argc, argv); }
