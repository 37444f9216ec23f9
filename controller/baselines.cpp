/// @file
/// The field's baseline controllers (docs/baselines.md), registered through
/// the controller seam (controller/registry.hpp) like any controller from
/// outside the paper: each programme that reads scenarios links this object
/// (controller/CMakeLists.txt, lagrange_controller_kinds), so every process of a
/// run knows the types.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "config/key_table.hpp"
#include "controller/berghuis_nijmeijer.hpp"
#include "controller/nicosia_tomei.hpp"
#include "controller/pd_plus_differenced.hpp"
#include "controller/registry.hpp"
#include "controller/set_point.hpp"
#include "controller/velocity_feedback.hpp"

namespace lagrange::controller {
namespace {

// A core stepping on (t, q) alone -- the position-only baselines -- as a
// Controller. The model and the reference live here; the core refers to them.
template <class Core>
class PositionOnly final : public Controller {
 public:
  template <class... Gains>
  PositionOnly(const config::Scenario& s, Gains&&... gains)
      : model_(s.robotModel()),
        reference_(s.reference),
        core_(*model_, reference_, std::forward<Gains>(gains)...) {}
  Needs needs() const override { return {}; }
  ControllerCommand step(const ControllerInputs& in) override { return core_.step(in.t, in.q); }
  void reset() override { core_.reset(); }

 private:
  const model::RobotModelPtr model_;
  const model::Reference reference_;
  Core core_;
};

// A core stepping on (t, q, q') -- the baselines that measure the velocity --
// as a Controller: it declares joint rates, so it gets PLANT_RATE.
template <class Core>
class WithVelocity final : public Controller {
 public:
  WithVelocity(const config::Scenario& s, const Eigen::VectorXd& gain1, const Eigen::VectorXd& gain2)
      : model_(s.robotModel()), reference_(s.reference), core_(*model_, reference_, gain1, gain2) {}
  Needs needs() const override {
    Needs n;
    n.joint_rates = true;
    return n;
  }
  ControllerCommand step(const ControllerInputs& in) override { return core_.step(in.t, in.q, in.qdot); }
  void reset() override { core_.reset(); }

 private:
  const model::RobotModelPtr model_;
  const model::Reference reference_;
  Core core_;
};

// The gain report of a baseline whose paper's claim the tool states but does
// not evaluate (GainReport::unchecked carries the sentence).
std::function<GainReport(const config::Scenario&, bool)> claimOnly(std::string claim) {
  return [claim = std::move(claim)](const config::Scenario&, bool) {
    GainReport r;
    r.unchecked = claim;
    return r;
  };
}

// The ranges `lagrange tune` searches (docs/tuning.md), per joint, on a log
// scale; the search box is narrowed about the scenario's own gains.
const TunableGain kKp{"kp", true, 1e-2, 1e5, 100.0};
const TunableGain kKd{"kd", true, 1e-3, 1e4, 10.0};
const TunableGain kFilterA{"a", true, 1.0, 1e5, 50.0};
const TunableGain kFilterB{"b", true, 1.0, 1e5, 50.0};
const TunableGain kLambda{"lambda", true, 1e-2, 1e4, 10.0};
const TunableGain kObserverLp{"lp", true, 1.0, 1e8, 1e4};
const TunableGain kObserverLd{"ld", true, 1.0, 1e5, 200.0};

// PD+ and Slotine-Li need no condition beyond positive gains (with the
// velocity measured and the model exact); the report states the claim.
ControllerKind velocityKind(std::string type, std::vector<config::ControllerParam> keys,
                            std::function<std::unique_ptr<Controller>(const config::Scenario&)> make,
                            std::string claim, std::vector<TunableGain> tunable) {
  ControllerKind kind{std::move(type), std::move(keys), std::move(make), claimOnly(std::move(claim))};
  kind.measures_velocity = true;
  kind.tunable = std::move(tunable);
  return kind;
}

const bool kPdPlusRegistered = registerControllerKind(velocityKind(
    "pd_plus",
    {{"kp", true, "stiffness Kp [N m / rad]"}, {"kd", true, "damping Kd on q' - q_d' [N m s / rad]"}},
    [](const config::Scenario& s) {
      return std::make_unique<WithVelocity<PdPlus>>(s, s.controller.params.at("kp"),
                                                    s.controller.params.at("kd"));
    },
    "pd_plus: Paden and Panja (Int. J. Control 1988) prove global (asymptotic) tracking for every positive "
    "Kp, Kd, with the velocity measured and the model exact, so there is no further condition to check; the "
    "sensors and the sampled implementation are not assessed",
    {kKp, kKd}));

const bool kSlotineLiRegistered = registerControllerKind(velocityKind(
    "slotine_li",
    {{"lambda", true, "Lambda in q_r' = q_d' - Lambda q~ [1/s]"},
     {"kd", true, "damping KD on s = q' - q_r' [N m s / rad]"}},
    [](const config::Scenario& s) {
      return std::make_unique<WithVelocity<SlotineLi>>(s, s.controller.params.at("lambda"),
                                                       s.controller.params.at("kd"));
    },
    "slotine_li: Slotine and Li (Int. J. Robotics Research 1987) prove global (asymptotic) tracking for "
    "every positive Lambda, KD, with the velocity measured and the model exact, so there is no further "
    "condition to check; the sensors and the sampled implementation are not assessed",
    {kLambda, kKd}));

// PD+ with a differenced velocity claims nothing (docs/baselines.md): no gain
// condition, and the report says its gains are not checked.
const bool kPdPlusDifferencedRegistered = registerControllerKind(
    withTunable({"pd_plus_differenced",
                 {{"kp", true, "stiffness Kp [N m / rad]"},
                  {"kd", true, "damping Kd on the differenced velocity [N m s / rad]"}},
                 [](const config::Scenario& s) {
                   return std::make_unique<PositionOnly<PdPlusDifferenced>>(s, s.controller.params.at("kp"),
                                                                            s.controller.params.at("kd"));
                 },
                 {}},
                {kKp, kKd}));

// Kelly (1993) states no condition beyond positive gains: the report says so
// instead of inventing one. The sampled-data check covers the paper's
// controllers only.
const bool kSetPointRegistered = registerControllerKind(
    withTunable({"set_point",
                 {{"kp", true, "stiffness Kp [N m / rad]"},
                  {"kd", true, "damping Kd on the filtered rate theta [N m s / rad when b = a]"},
                  {"a", true, "filter pole a [1/s]"},
                  {"b", true, "filter gain b [1/s]"}},
                 [](const config::Scenario& s) {
                   const auto& p = s.controller.params;
                   return std::make_unique<PositionOnly<SetPoint>>(
                       s, Theorem1Gains{p.at("kp"), p.at("kd"), p.at("a"), p.at("b")});
                 },
                 claimOnly("set_point: Kelly (IFAC 1993) proves global asymptotic regulation to a "
                           "constant q_d for every positive kp, kd, a, b with exact gravity "
                           "compensation, so there is no further condition to check; the sampled "
                           "implementation is not assessed"),
                 /*set_point=*/true},
                {kKp, kKd, kFilterA, kFilterB}));

// Nicosia and Tomei's conditions bound the gains by the model's and the
// reference's constants and hold in a region around the reference: not
// evaluated here, and the report says so.
const bool kNicosiaTomeiRegistered = registerControllerKind(withTunable(
    {"nicosia_tomei",
     {{"kp", true, "stiffness Kp [N m / rad]"},
      {"kd", true, "damping Kd on the estimated velocity [N m s / rad]"},
      {"lp", true, "observer gain Lp on q - qh in zh' [1/s^2]"},
      {"ld", true, "observer gain Ld on q - qh in qh' [1/s]"}},
     [](const config::Scenario& s) {
       const auto& p = s.controller.params;
       return std::make_unique<PositionOnly<NicosiaTomei>>(
           s, NicosiaTomeiGains{p.at("kp"), p.at("kd"), p.at("lp"), p.at("ld")});
     },
     claimOnly(
         "nicosia_tomei: Nicosia and Tomei (IEEE TAC 1990) prove local tracking, for gains large enough in "
         "terms of the model's and the reference's bounds; those conditions are not evaluated here, and the "
         "sampled implementation is not assessed")},
    {kKp, kKd, kObserverLp, kObserverLd}));

const bool kBerghuisNijmeijerRegistered = registerControllerKind(withTunable(
    {"berghuis_nijmeijer",
     {{"kp", true, "stiffness Kp [N m / rad]"},
      {"kd", true, "damping Kd on q0' - qr' [N m s / rad]"},
      {"lambda", true, "Lambda in qr' = q_d' - Lambda (qh - q_d) [1/s]"},
      {"lp", true, "observer gain Lp on q - qh in zh' [1/s^2]"},
      {"ld", true, "observer gain Ld on q - qh in qh' [1/s]"}},
     [](const config::Scenario& s) {
       const auto& p = s.controller.params;
       return std::make_unique<PositionOnly<BerghuisNijmeijer>>(
           s, BerghuisNijmeijerGains{p.at("kp"), p.at("kd"), p.at("lambda"), p.at("lp"), p.at("ld")});
     },
     claimOnly(
         "berghuis_nijmeijer: Berghuis and Nijmeijer (IEEE TRA 1993) prove semiglobal exponential tracking, "
         "the region of attraction growing with the gains; their conditions are not evaluated here, and the "
         "sampled implementation is not assessed")},
    {kKp, kKd, kLambda, kObserverLp, kObserverLd}));

// The baselines' gains that are no paper controller's (kp, kd, a, b are, and
// their rows hold them): their ranges and the hint an unknown-key message gives.
const bool kBaselineKeysRegistered = [] {
  using namespace config::keyrow;
  config::registerKeyRows("registered", "the baselines that declare it (docs/baselines.md)",
                          {only("registered", inside("controller.lambda", "controller.type", gain())),
                           only("registered", inside("controller.ld", "controller.type", gain())),
                           only("registered", inside("controller.lp", "controller.type", gain()))});
  return true;
}();

}  // namespace
}  // namespace lagrange::controller
