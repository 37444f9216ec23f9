// Google Benchmark micro-benchmarks of the cores: model terms, controller
// step, actuator step, for chains of 2 to 20 joints.
#include <benchmark/benchmark.h>

#include "actuator/integrator_chain.hpp"
#include "controller/theorem1.hpp"
#include "model/planar_chain.hpp"

namespace {

lagrange::model::ChainParams chain(int n) {
  lagrange::model::ChainParams p;
  for (int i = 0; i < n; ++i) p.links.push_back({0.1, 0.05, 0.2, 1.7e-4});
  return p;
}

lagrange::model::Reference reference(int n) {
  lagrange::model::ReferenceParams p;
  p.type = lagrange::model::ReferenceType::kSine;
  p.offset = Eigen::VectorXd::Constant(n, 0.1);
  p.amplitude = Eigen::VectorXd::Constant(n, 0.1);
  p.frequency = Eigen::VectorXd::Constant(n, 2.0);
  p.phase = Eigen::VectorXd::Zero(n);
  return lagrange::model::Reference(p);
}

void BM_Inertia(benchmark::State& state) {
  const lagrange::model::PlanarChain c(chain(static_cast<int>(state.range(0))));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c.dof(), 0.1, 1.0);
  for (auto _ : state) benchmark::DoNotOptimize(c.inertia(q));
}
void BM_Coriolis(benchmark::State& state) {
  const lagrange::model::PlanarChain c(chain(static_cast<int>(state.range(0))));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c.dof(), 0.1, 1.0), v = q;
  for (auto _ : state) benchmark::DoNotOptimize(c.coriolis(q, v));
}
void BM_Gravity(benchmark::State& state) {
  const lagrange::model::PlanarChain c(chain(static_cast<int>(state.range(0))));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c.dof(), 0.1, 1.0);
  for (auto _ : state) benchmark::DoNotOptimize(c.gravity(q));
}
void BM_ControllerStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const lagrange::model::PlanarChain c(chain(n));
  const lagrange::model::Reference r = reference(n);
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(n);
  lagrange::controller::Theorem1Controller ctl(c, r, {one, one, 50 * one, 50 * one}, std::nullopt);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, 0.1, 1.0);
  double t = 0.0;
  for (auto _ : state) benchmark::DoNotOptimize(ctl.step(t += 1e-3, q));
}
void BM_ActuatorStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  lagrange::actuator::IntegratorChain act(n, 0, Eigen::VectorXd::Constant(n, 10.0), Eigen::MatrixXd(0, n));
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(n, -20.0, 20.0);
  for (auto _ : state) benchmark::DoNotOptimize(act.step(u, 1e-3));
}

BENCHMARK(BM_Inertia)->Arg(2)->Arg(5)->Arg(10)->Arg(20);
BENCHMARK(BM_Coriolis)->Arg(2)->Arg(5)->Arg(10)->Arg(20);
BENCHMARK(BM_Gravity)->Arg(2)->Arg(5)->Arg(10)->Arg(20);
BENCHMARK(BM_ControllerStep)->Arg(2)->Arg(5)->Arg(10)->Arg(20);
BENCHMARK(BM_ActuatorStep)->Arg(2)->Arg(20);

}  // namespace

BENCHMARK_MAIN();
