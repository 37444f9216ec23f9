/// @file
/// The field's baseline controllers (docs/baselines.md), registered through
/// the controller seam (controller/registry.hpp) like any controller from
/// outside the paper: each programme that reads scenarios links this object
/// (controller/CMakeLists.txt, lagrange_baselines), so every process of a
/// run knows the types.
#include <memory>
#include <optional>

#include "controller/pd_plus_differenced.hpp"
#include "controller/registry.hpp"

namespace lagrange::controller {
namespace {

class PdPlusDifferencedController final : public Controller {
 public:
  explicit PdPlusDifferencedController(const config::Scenario& s)
      : model_(s.robotModel()),
        reference_(s.reference),
        core_(*model_, reference_, s.controller.params.at("kp"), s.controller.params.at("kd")) {}
  Needs needs() const override { return {}; }  // positions only
  ControllerCommand step(const ControllerInputs& in) override { return core_.step(in.t, in.q); }
  void reset() override { core_.reset(); }

 private:
  const model::RobotModelPtr model_;
  const model::Reference reference_;
  PdPlusDifferenced core_;
};

// PD+ with a differenced velocity claims nothing (docs/baselines.md): no gain
// condition, and the report says its gains are not checked.
const bool kRegistered = registerControllerKind(
    {"pd_plus_differenced",
     {{"kp", true, "stiffness Kp [N m / rad]"},
      {"kd", true, "damping Kd on the differenced velocity [N m s / rad]"}},
     [](const config::Scenario& s) { return std::make_unique<PdPlusDifferencedController>(s); },
     {}});

}  // namespace
}  // namespace lagrange::controller
