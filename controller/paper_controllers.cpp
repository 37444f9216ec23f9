#include "controller/paper_controllers.hpp"

#include <optional>

#include "controller/cascaded.hpp"
#include "controller/flexible.hpp"
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
    core_.emplace(*model_, reference_, s_.controller.gains, s_.controller.initial_filter_state);
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
    core_.emplace(*model_, reference_, CascadedGains{s_.controller.gains, s_.controller.stages},
                  s_.controller.initial_filter_state, s_.controller.stage_starts);
  }

 private:
  std::optional<CascadedController> core_;
};

class Flexible final : public PaperController {
 public:
  explicit Flexible(const config::Scenario& s) : PaperController(s) { reset(); }
  Needs needs() const override { return {0, true, s_.controller.motor_rate == config::MotorRate::kMeasured}; }
  ControllerCommand step(const ControllerInputs& in) override {
    const FlexibleController::Output out = core_->step(in.t, in.q, in.motor_q, in.motor_qdot);
    return withCascade(out.cascade, out.tau);
  }
  void reset() override {
    core_.emplace(*model_, reference_, CascadedGains{s_.controller.gains, s_.controller.stages},
                  s_.controller.initial_filter_state, s_.flexible->params,
                  s_.controller.motor_rate == config::MotorRate::kFiltered
                      ? std::optional(s_.controller.motor_rate_pole)
                      : std::nullopt,
                  s_.controller.stage_starts);
  }

 private:
  std::optional<FlexibleController> core_;
};

template <class C>
ControllerKind paperKind(const char* type) {
  return {type, {}, [](const config::Scenario& s) { return std::make_unique<C>(s); }, checkPaperGains};
}

}  // namespace

std::vector<ControllerKind> paperControllerKinds() {
  return {paperKind<Theorem1>("theorem1"), paperKind<Cascaded>("cascaded"), paperKind<Flexible>("flexible")};
}

}  // namespace lagrange::controller
