#include "controller/paper_controllers.hpp"

#include <optional>

#include "controller/cascaded.hpp"
#include "controller/flexible.hpp"
#include "controller/paper_section.hpp"
#include "controller/theorem1.hpp"

namespace lagrange::controller {

namespace {

// What the three share: the model the controller uses (for flexible joints
// the links with their springs, eq. 608), the reference, and the scenario to
// rebuild from on reset.
class PaperController : public Controller {
 protected:
  explicit PaperController(const config::Scenario& s)
      : s_(s), model_(s.controlModel()), reference_(s.reference) {}
  const PaperSettings& settings() const { return paperSettings(s_); }
  const config::Scenario s_;
  const model::RobotModelPtr model_;
  const model::Reference reference_;
};

ControllerCommand withCascade(const CascadedController::Output& out, const Eigen::VectorXd& u) {
  ControllerCommand command = out.stage0;
  command.u = u;
  command.xi_error = out.cascade.xi_error;
  return command;
}

class Theorem1 final : public PaperController {
 public:
  explicit Theorem1(const config::Scenario& s) : PaperController(s) { reset(); }
  Needs needs() const override { return {}; }
  ControllerCommand step(const ControllerInputs& in) override { return core_->step(in.t, in.q); }
  void reset() override {
    core_.emplace(*model_, reference_, settings().gains, settings().initial_filter_state);
  }

 private:
  std::optional<Theorem1Controller> core_;
};

class Cascaded final : public PaperController {
 public:
  explicit Cascaded(const config::Scenario& s) : PaperController(s) { reset(); }
  Needs needs() const override { return {s_.actuator.order, false, false}; }
  ControllerCommand step(const ControllerInputs& in) override {
    const CascadedController::Output out = core_->step(in.t, in.q, in.xi);
    return withCascade(out, out.cascade.u);
  }
  void reset() override {
    core_.emplace(*model_, reference_, CascadedGains{settings().gains, settings().stages},
                  settings().initial_filter_state, settings().stage_starts);
  }

 private:
  std::optional<CascadedController> core_;
};

class Flexible final : public PaperController {
 public:
  explicit Flexible(const config::Scenario& s) : PaperController(s) { reset(); }
  Needs needs() const override { return {0, true, settings().motor_rate == MotorRate::kMeasured}; }
  ControllerCommand step(const ControllerInputs& in) override {
    const FlexibleController::Output out = core_->step(in.t, in.q, in.motor_q, in.motor_qdot);
    return withCascade(out.cascade, out.tau);
  }
  void reset() override {
    core_.emplace(*model_, reference_, CascadedGains{settings().gains, settings().stages},
                  settings().initial_filter_state, s_.flexible->params,
                  settings().motor_rate == MotorRate::kFiltered ? std::optional(settings().motor_rate_pole)
                                                                : std::nullopt,
                  settings().stage_starts);
  }

 private:
  std::optional<FlexibleController> core_;
};

template <class C>
ControllerKind paperKind(const char* type, int listing) {
  ControllerKind kind;
  kind.type = type;
  kind.make = [](const config::Scenario& s) { return std::make_unique<C>(s); };
  kind.report = checkPaperGains;
  kind.section = paperSectionCodec();
  kind.listing = listing;
  // Stage 0's gains, per joint, and a chain's later stages' the same
  // (theorem1 has none). Wide ranges: the search box is narrowed about the
  // scenario's own gains (docs/tuning.md).
  kind.tunable = {{"kp", true, 1e-2, 1e5, 100.0},       {"kd", true, 1e-3, 1e4, 10.0},
                  {"a", true, 1.0, 1e5, 50.0},          {"b", true, 1.0, 1e5, 50.0},
                  {"kp", true, 1e-2, 1e5, 100.0, true}, {"kd", true, 1e-3, 1e4, 1.0, true},
                  {"a", true, 1.0, 1e5, 100.0, true},   {"b", true, 1.0, 1e5, 100.0, true}};
  return kind;
}

}  // namespace

std::vector<ControllerKind> paperControllerKinds() {
  ControllerKind flexible = paperKind<Flexible>("flexible", 2);
  flexible.elastic_joints_title = "the flexible controller (eq. (83))";
  return {paperKind<Theorem1>("theorem1", 0), paperKind<Cascaded>("cascaded", 1), flexible};
}

namespace {
// The one registration of the three, and of their section's keys.
const bool registered = [] {
  config::registerKeyRows(
      "paper",
      "the paper's controllers (controller.type theorem1, cascaded, flexible) and of the baselines that "
      "declare it (docs/baselines.md)",
      paperKeyRows());
  for (ControllerKind& kind : paperControllerKinds()) registerControllerKind(std::move(kind));
  return true;
}();
}  // namespace

}  // namespace lagrange::controller
