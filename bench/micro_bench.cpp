// Google Benchmark micro-benchmarks of the cores: model terms, the
// controller's feedforward and step, the actuator step -- planar chains of
// 2 to 20 joints next to the URDF arms (the Panda, 7 joints; the UR5, 6).
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

#include "actuator/integrator_chain.hpp"
#include "controller/theorem1.hpp"
#include "model/planar_chain.hpp"
#include "model/urdf_arm.hpp"

namespace {

using lagrange::model::RobotModelPtr;

lagrange::model::ChainParams chain(int n) {
  lagrange::model::ChainParams p;
  for (int i = 0; i < n; ++i) p.links.push_back({0.1, 0.05, 0.2, 1.7e-4});
  return p;
}

// Arguments 2..20: a planar chain of that many joints; 1007 the Panda, 1006 the UR5.
constexpr int kPanda = 1007, kUr5 = 1006;

std::string robotFile(const std::string& name) {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/robots/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

RobotModelPtr arm(int64_t which) {
  if (which == kPanda)
    return lagrange::model::UrdfArm::build(
        {robotFile("panda.urdf"), "panda.urdf", "panda_link0", "panda_hand", 9.81});
  if (which == kUr5)
    return lagrange::model::UrdfArm::build(
        {robotFile("ur5_robot.urdf"), "ur5_robot.urdf", "base_link", "tool0", 9.81});
  return std::make_shared<lagrange::model::PlanarChain>(chain(static_cast<int>(which)));
}

void label(benchmark::State& state) {
  state.SetLabel(state.range(0) == kPanda ? "panda" : state.range(0) == kUr5 ? "ur5" : "planar");
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
  const RobotModelPtr c = arm(state.range(0));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c->dof(), 0.1, 1.0);
  for (auto _ : state) benchmark::DoNotOptimize(c->inertia(q));
  label(state);
}
void BM_Coriolis(benchmark::State& state) {
  const RobotModelPtr c = arm(state.range(0));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c->dof(), 0.1, 1.0), v = q;
  for (auto _ : state) benchmark::DoNotOptimize(c->coriolis(q, v));
  label(state);
}
// C(q, v) w as the baselines need it every tick, without the matrix.
void BM_CoriolisTimes(benchmark::State& state) {
  const RobotModelPtr c = arm(state.range(0));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c->dof(), 0.1, 1.0), v = q, w = 0.5 * q;
  for (auto _ : state) benchmark::DoNotOptimize(c->coriolisTimes(q, v, w));
  label(state);
}
void BM_Gravity(benchmark::State& state) {
  const RobotModelPtr c = arm(state.range(0));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c->dof(), 0.1, 1.0);
  for (auto _ : state) benchmark::DoNotOptimize(c->gravity(q));
  label(state);
}
// The feedforward D(q) a + C(q, v) v + g(q) as the controllers compute it
// (the kind's inverse dynamics) and from the matrices (how the planar
// controller computed it before: C from all Christoffel partials).
void BM_InverseDynamics(benchmark::State& state) {
  const RobotModelPtr c = arm(state.range(0));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c->dof(), 0.1, 1.0), v = q, a = -q;
  for (auto _ : state) benchmark::DoNotOptimize(c->inverseDynamics(q, v, a));
  label(state);
}
void BM_FeedforwardFromMatrices(benchmark::State& state) {
  const RobotModelPtr c = arm(state.range(0));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c->dof(), 0.1, 1.0), v = q, a = -q;
  for (auto _ : state)
    benchmark::DoNotOptimize(Eigen::VectorXd(c->inertia(q) * a + c->coriolis(q, v) * v + c->gravity(q)));
  label(state);
}
// Forward dynamics D(q)^-1 (u - C v - g), per tick of a free_motion
// reference and of the Nicosia-Tomei observer: D, the bias from the inverse
// dynamics, and the Cholesky solve (the one O(n^3) step left on a tick).
void BM_ForwardDynamics(benchmark::State& state) {
  const RobotModelPtr c = arm(state.range(0));
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c->dof(), 0.1, 1.0), v = q, u = -q;
  for (auto _ : state) benchmark::DoNotOptimize(c->acceleration(q, v, u));
  label(state);
}
void BM_ControllerStep(benchmark::State& state) {
  const RobotModelPtr c = arm(state.range(0));
  const int n = c->dof();
  const lagrange::model::Reference r = reference(n);
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(n);
  lagrange::controller::Theorem1Controller ctl(*c, r, {one, one, 50 * one, 50 * one}, std::nullopt);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, 0.1, 1.0);
  double t = 0.0;
  for (auto _ : state) benchmark::DoNotOptimize(ctl.step(t += 1e-3, q));
  label(state);
}
void BM_ActuatorStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  lagrange::actuator::IntegratorChain act(n, 0, Eigen::VectorXd::Constant(n, 10.0), Eigen::MatrixXd(0, n));
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(n, -20.0, 20.0);
  for (auto _ : state) benchmark::DoNotOptimize(act.step(u, 1e-3));
}

void arms(benchmark::internal::Benchmark* b) {
  for (int which : {2, 5, 7, 10, 20, kUr5, kPanda}) b->Arg(which);
}
BENCHMARK(BM_Inertia)->Apply(arms);
BENCHMARK(BM_Coriolis)->Apply(arms);
BENCHMARK(BM_CoriolisTimes)->Apply(arms);
BENCHMARK(BM_Gravity)->Apply(arms);
BENCHMARK(BM_InverseDynamics)->Apply(arms);
BENCHMARK(BM_FeedforwardFromMatrices)->Apply(arms);
BENCHMARK(BM_ForwardDynamics)->Apply(arms);
BENCHMARK(BM_ControllerStep)->Apply(arms);
BENCHMARK(BM_ActuatorStep)->Arg(2)->Arg(20);

}  // namespace

BENCHMARK_MAIN();
