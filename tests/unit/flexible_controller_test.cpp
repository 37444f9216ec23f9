// The flexible-joint controller (eq. (83)) is the m = 2 cascade on
// xi = [K q2; K q2'] with the link model g + K q, plus the torque map (830a).
#include <gtest/gtest.h>

#include <cmath>

#include "controller/flexible.hpp"
#include "model/joint_springs.hpp"
#include "model/planar_chain.hpp"

namespace lagrange::controller {
namespace {

struct Arm {
  model::FlexibleParams params{Eigen::Vector2d(100.0, 30.0), Eigen::Vector2d(0.05, 0.02)};
  model::JointSprings links;
  model::Reference reference;
  CascadedGains gains;
  Arm()
      : links(std::make_shared<model::PlanarChain>(model::pelicanParams()), params.stiffness), reference([] {
          model::ReferenceParams r;
          r.type = model::ReferenceType::kSine;
          r.offset = Eigen::Vector2d(0.3, 0.2);
          r.amplitude = Eigen::Vector2d(0.1, 0.1);
          r.frequency = Eigen::Vector2d(2.0, 3.0);
          r.phase = Eigen::Vector2d::Zero();
          return r;
        }()) {
    gains.stage0 = {Eigen::Vector2d(150, 10), Eigen::Vector2d(15, 1), Eigen::Vector2d(50, 50),
                    Eigen::Vector2d(50, 50)};
    const StageGains st{Eigen::Vector2d::Constant(300), Eigen::Vector2d::Constant(1),
                        Eigen::Vector2d::Constant(600), Eigen::Vector2d::Constant(600)};
    gains.stages = {st, StageGains{Eigen::Vector2d::Constant(900), st.kd, st.a, st.b}};
  }
};

TEST(FlexibleController, IsTheCascadeOnKq2WithTheTorqueMap830a) {
  Arm s;
  FlexibleController flexible(s.links, s.reference, s.gains, std::nullopt, s.params, std::nullopt);
  CascadedController cascade(s.links, s.reference, s.gains, std::nullopt);
  const Eigen::Vector2d q1(0.5, -0.2), q2(0.6, -0.1), q2dot(0.3, -0.4);
  for (int k = 0; k < 3; ++k) {
    const double t = k * 1e-3;
    const auto out = flexible.step(t, q1, q2 + k * 1e-3 * q2dot, q2dot);
    Eigen::MatrixXd xi(2, 2);
    xi.row(0) = s.params.stiffness.cwiseProduct(q2 + k * 1e-3 * q2dot).transpose();
    xi.row(1) = s.params.stiffness.cwiseProduct(q2dot).transpose();
    const auto ref = cascade.step(t, q1, xi);
    EXPECT_EQ(out.cascade.cascade.u, ref.cascade.u);
    const Eigen::Vector2d expected =
        s.params.stiffness.cwiseProduct(q2 + k * 1e-3 * q2dot - q1) +
        s.params.rotor_inertia.cwiseProduct(ref.cascade.u).cwiseQuotient(s.params.stiffness);
    EXPECT_LT((out.tau - expected).norm(), 1e-9 * (1.0 + expected.norm()));
  }
  EXPECT_THROW(flexible.step(1.0, q1, q2, std::nullopt), std::invalid_argument);  // measured rate missing
}

TEST(FlexibleController, FilteredRateStartsAtZeroAndFollowsARamp) {
  Arm s;
  FlexibleController flexible(s.links, s.reference, s.gains, std::nullopt, s.params,
                              Eigen::Vector2d(300, 300));
  const Eigen::Vector2d q1(0.5, -0.2), q2(0.6, -0.1), rate(0.3, -0.4);
  EXPECT_EQ(flexible.step(0.0, q1, q2, std::nullopt).motor_rate, Eigen::Vector2d::Zero());  // bumpless
  Eigen::VectorXd estimate;
  for (int k = 1; k <= 200; ++k)
    estimate = flexible.step(k * 1e-3, q1, q2 + k * 1e-3 * rate, std::nullopt).motor_rate;
  // After 0.2 s (60 time constants) the estimate of the sampled, held ramp is
  // steady at slope x aT / (1 - exp(-aT)): 1.157 x the slope for aT = 0.3, the
  // bias of differentiating a staircase (it vanishes as aT -> 0).
  const double at = 300.0 * 1e-3, bias = at / (1.0 - std::exp(-at));
  EXPECT_LT((estimate - bias * rate).norm(), 1e-9);
}

}  // namespace
}  // namespace lagrange::controller
