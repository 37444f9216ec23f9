#pragma once
/// @file
/// Classic fourth-order Runge-Kutta and the analytic closed loops the tests
/// compare the product against. Written from the equations, independently of
/// the ODE plant.

#include <Eigen/Dense>

#include "model/planar_chain.hpp"

namespace lagrange::testing {

template <class F>
Eigen::VectorXd rk4Step(const F& f, double t, const Eigen::VectorXd& x, double h) {
  const Eigen::VectorXd k1 = f(t, x);
  const Eigen::VectorXd k2 = f(t + h / 2, x + h / 2 * k1);
  const Eigen::VectorXd k3 = f(t + h / 2, x + h / 2 * k2);
  const Eigen::VectorXd k4 = f(t + h, x + h * k3);
  return x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
}

/// x = [q; q'] of eq. (10) under a torque held constant over the step.
inline Eigen::VectorXd armStep(const model::RobotModel& chain, const Eigen::VectorXd& x,
                               const Eigen::VectorXd& tau, double h) {
  const int n = chain.dof();
  auto f = [&](double, const Eigen::VectorXd& s) {
    Eigen::VectorXd d(2 * n);
    d.head(n) = s.tail(n);
    d.tail(n) = chain.acceleration(s.head(n), s.tail(n), tau);
    return d;
  };
  return rk4Step(f, 0.0, x, h);
}

}  // namespace lagrange::testing
