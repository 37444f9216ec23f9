// A controller that exists only in the tests, to prove the controller seam:
// this file alone defines and registers it, and the project's own process
// mains, linked with it (tests/CMakeLists.txt, bin-test-controller/), run it
// in every wiring. Nothing outside tests/ names it.
//
// test_pd: u = g(q) - kp (q - q_d(t)) - kd (q - q_prev) / (t - t_prev), a
// PD with gravity compensation whose rate is a backward difference of the
// measured positions (0 at the first sample). No stability theory is
// claimed for it, so its gains are not checked.
#include <memory>

#include "controller/registry.hpp"
#include "model/planar_chain.hpp"
#include "model/reference.hpp"

namespace lagrange::testing {
namespace {

class TestPd final : public controller::Controller {
 public:
  explicit TestPd(const config::Scenario& s)
      : arm_(s.robot),
        reference_(s.reference),
        kp_(s.controller.params.at("kp")),
        kd_(s.controller.params.at("kd")) {}

  controller::Needs needs() const override { return {}; }  // positions only

  controller::ControllerCommand step(const controller::ControllerInputs& in) override {
    const Eigen::VectorXd q_d = reference_.evaluate(in.t, 0).q();
    const Eigen::VectorXd rate = previous_q_ ? Eigen::VectorXd((in.q - *previous_q_) / (in.t - previous_t_))
                                             : Eigen::VectorXd::Zero(in.q.size());
    controller::ControllerCommand c;
    c.q_desired = q_d;
    c.q_error = in.q - q_d;
    c.theta = rate;  // the diagnostic slot of a filtered rate: here the backward difference
    c.u = arm_.gravity(in.q) - kp_.cwiseProduct(c.q_error) - kd_.cwiseProduct(rate);
    previous_q_ = in.q;
    previous_t_ = in.t;
    return c;
  }

  void reset() override { previous_q_.reset(); }

 private:
  const model::PlanarChain arm_;
  const model::Reference reference_;
  const Eigen::VectorXd kp_, kd_;
  std::optional<Eigen::VectorXd> previous_q_;
  double previous_t_ = 0.0;
};

// Its tunable gains: kp per joint, kd one value for every joint (the seam's
// scalar case, which lagrange tune writes as one number).
const bool registered = controller::registerControllerKind(controller::withTunable(
    {"test_pd",
     {{"kp", true, "stiffness [N m/rad]"}, {"kd", true, "damping on the differenced rate [N m s/rad]"}},
     [](const config::Scenario& s) { return std::make_unique<TestPd>(s); },
     {}},
    {{"kp", true, 1e-2, 1e5, 100.0}, {"kd", false, 1e-3, 1e4, 10.0}}));

}  // namespace
}  // namespace lagrange::testing
