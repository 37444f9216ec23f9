/// @file
/// `lagrange-bench-engines`: accuracy per CPU second of the physics engines
/// (docs/engines_and_arms.md, "Two engines: accuracy per CPU second";
/// bench/engine_accuracy.sh runs it). One scenario's closed loop -- the same
/// controller, actuator and tick order as wiring::simulateInProcess, without
/// the messages (the table's header shows both give the same numbers) -- on
/// each engine at each physics step, against a reference solution of the same
/// closed loop; then the plant alone, fed the run's own torques again, timed
/// on the thread's CPU clock. Prints and writes one row per engine and step
/// (TSV): the convergence time's error relative to the reference's, the
/// largest joint-angle gap to the reference over the run, and CPU seconds per
/// simulated second of the plant's stepping and of the whole loop.
///
/// The reference (--reference): RK4 of the controllers' own model
/// (model::RobotModel::acceleration, the torque held over each step) at 1e-6 s
/// by default; or, cheaper, MuJoCo's RK4 at a fine step, checked against RK4
/// of the model over the run's first seconds. A study, not a test: nothing
/// here is asserted.

#include <time.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "actuator/integrator_chain.hpp"
#include "config/scenario.hpp"
#include "controller/registry.hpp"
#include "logger/tracking_metrics.hpp"
#include "model/reference.hpp"
#include "plant/plant_sim.hpp"
#include "plant/scenario_plant.hpp"
#include "wiring/inproc_runner.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using lagrange::config::Scenario;

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// What the closed loop steps: an engine's plant, or RK4 of the model.
class Plant {
 public:
  virtual ~Plant() = default;
  /// One control period: tau's rows held over equal parts of `substeps` steps.
  virtual void stepProfile(const MatrixXd& tau, int substeps) = 0;
  virtual VectorXd q() const = 0;
};

class EnginePlant : public Plant {
 public:
  explicit EnginePlant(const Scenario& s) : sim_(lagrange::plant::plantFor(s)) {}
  void stepProfile(const MatrixXd& tau, int substeps) override { sim_.stepProfile(tau, substeps); }
  VectorXd q() const override { return sim_.state().q; }

 private:
  lagrange::plant::PlantSim sim_;
};

/// Classic RK4 of D(q) q'' + C(q, q') q' + g(q) = tau, tau held over each
/// step: the arm as the controllers model it, written from the equations.
class ModelRk4Plant : public Plant {
 public:
  ModelRk4Plant(const Scenario& s, double step) : model_(s.robotModel()), h_(step), n_(s.dof()), x_(2 * n_) {
    x_ << s.initial_state.q, s.initial_state.qdot;
  }
  void stepProfile(const MatrixXd& tau, int substeps) override {
    const int parts = static_cast<int>(tau.rows());
    for (int p = 0; p < parts; ++p) {
      const VectorXd u = tau.row(p).transpose();
      for (int k = 0; k < substeps / parts; ++k) step(u);
    }
  }
  VectorXd q() const override { return x_.head(n_); }

 private:
  VectorXd f(const VectorXd& x, const VectorXd& u) const {
    VectorXd d(2 * n_);
    d.head(n_) = x.tail(n_);
    d.tail(n_) = model_->acceleration(x.head(n_), x.tail(n_), u);
    return d;
  }
  void step(const VectorXd& u) {
    const VectorXd k1 = f(x_, u);
    const VectorXd k2 = f(x_ + h_ / 2 * k1, u);
    const VectorXd k3 = f(x_ + h_ / 2 * k2, u);
    const VectorXd k4 = f(x_ + h_ * k3, u);
    x_ += h_ / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }

  lagrange::model::RobotModelPtr model_;
  double h_;
  int n_;
  VectorXd x_;
};

struct Trajectory {
  std::vector<VectorXd> q;    ///< per tick
  std::vector<double> error;  ///< ||q - q_d|| per tick [rad]
  std::vector<MatrixXd> tau;  ///< the torque profile applied after each tick
  std::string stopped;        ///< why the plant stopped the run (empty: it ran to the end)
  double loop_cpu = 0.0;      ///< the whole loop's thread CPU time [s]
};

/// The closed loop of wiring::simulateInProcess (ideal position sensor, the
/// lockstep order plant sample -> controller -> actuator -> physics) for
/// ticks 0..last_tick.
Trajectory closedLoop(const Scenario& s, Plant& plant, long long last_tick) {
  namespace ctl = lagrange::controller;
  const std::unique_ptr<ctl::Controller> controller = ctl::makeController(s);
  const ctl::Needs needs = controller->needs();
  ctl::InputAssembly assembly = ctl::makeInputAssembly(s, needs);
  lagrange::actuator::IntegratorChain act(s.dof(), s.actuator.order, s.actuator.saturation,
                                          s.actuator.initial_state);
  const lagrange::model::Reference reference(s.reference);
  Trajectory out;
  const double start = threadCpuSeconds();
  for (long long k = 0; k <= last_tick; ++k) {
    const double t = static_cast<double>(k) * s.tickPeriod();
    const VectorXd q = plant.q();
    out.q.push_back(q);
    out.error.push_back((q - reference.evaluate(t, 0).q()).norm());
    const ctl::AssembledInputs in = assembly.forTick(k, t, q).value();
    const auto command = controller->step(in.inputs);
    const auto applied = act.step(command.u, s.tickPeriod(), s.torqueStepsPerTick());
    if (needs.actuator_order > 0) assembly.chainState(k, act.state());
    if (k == last_tick) break;
    out.tau.push_back(applied.tau);
    try {
      plant.stepProfile(applied.tau, s.substepsPerTick());
    } catch (const lagrange::plant::PlantStopped& stopped) {
      out.stopped = stopped.what();
      break;
    }
  }
  out.loop_cpu = threadCpuSeconds() - start;
  return out;
}

/// Thread CPU seconds of the plant alone over the run's own torques (what
/// closedLoop applied), on a fresh plant.
double plantCpu(const Scenario& s, const Trajectory& run) {
  EnginePlant plant(s);
  const double start = threadCpuSeconds();
  try {
    for (const MatrixXd& tau : run.tau) plant.stepProfile(tau, s.substepsPerTick());
  } catch (const lagrange::plant::PlantStopped&) {  // where the run stopped too
  }
  return threadCpuSeconds() - start;
}

/// The tick-sampled convergence time (logger::TrackingMetrics' rule: the
/// first sample after the last one at or above the tolerance), and the same
/// crossing interpolated between those two samples in log ||q~|| -- finer
/// than a tick, so that differences below 1 ms show.
struct Convergence {
  std::optional<double> sampled, interpolated;
};
Convergence convergence(const std::vector<double>& error, double period, double tolerance) {
  Convergence c;
  if (error.empty() || !(error.back() < tolerance)) return c;
  size_t last = error.size();
  for (size_t i = error.size(); i-- > 0;)
    if (error[i] >= tolerance) {
      last = i;
      break;
    }
  if (last == error.size()) {
    c.sampled = c.interpolated = 0.0;
    return c;
  }
  c.sampled = static_cast<double>(last + 1) * period;
  const double a = std::log(error[last]), b = std::log(error[last + 1]);
  c.interpolated = (static_cast<double>(last) + (a - std::log(tolerance)) / (a - b)) * period;
  return c;
}

/// max over the ticks both reached of max_i |a.q_i - b.q_i| [rad], and the tick where.
struct Gap {
  double value = 0.0;
  size_t tick = 0;
};
Gap maxGap(const Trajectory& a, const Trajectory& b) {
  Gap gap;
  const size_t n = std::min(a.q.size(), b.q.size());
  for (size_t k = 0; k < n; ++k)
    if (const double g = (a.q[k] - b.q[k]).cwiseAbs().maxCoeff(); g > gap.value) gap = {g, k};
  return gap;
}

std::string engineKey(const std::string& engine) { return engine == "mujoco" ? "mujoco" : "ode"; }

Scenario scenarioFor(const std::string& config, double duration, const std::string& engine, double step) {
  std::vector<std::string> sets = {"mode=inproc"};
  char buf[96];
  std::snprintf(buf, sizeof buf, "plant.physics_step=%.17g", step);
  sets.emplace_back(buf);
  std::snprintf(buf, sizeof buf, "duration=%.17g", duration);
  sets.emplace_back(buf);
  sets.push_back("plant.engine=" + engineKey(engine));
  if (engine == "mujoco") sets.emplace_back("plant.mujoco_integrator=rk4");
  return lagrange::config::loadScenario(config, sets);
}

std::string fmt(const std::optional<double>& v, const char* format = "%.6g") {
  if (!v || !std::isfinite(*v)) return "NA";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, *v);
  return buf;
}

std::vector<double> parseList(const std::string& text) {
  std::vector<double> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(std::stod(item));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Accuracy per CPU second of the physics engines on one scenario's closed loop"};
  std::string config, label, out_path, reference_kind = "model", engines_text = "ode,mujoco",
                                       steps_text = "1e-3,5e-4,2.5e-4,1e-4,5e-5,2.5e-5,1e-5";
  double duration = 0.0, reference_step = 1e-6, check_step = 1e-6, check_duration = 0.5;
  int repeats = 3;
  app.add_option("config", config, "Scenario YAML file")->required();
  app.add_option("--label", label, "The arm's name in the table (default: the scenario's name)");
  app.add_option("--duration", duration, "Simulated seconds per run (default: the scenario's)");
  app.add_option("--engines", engines_text, "Engines, comma-separated: ode, mujoco (RK4)");
  app.add_option("--steps", steps_text, "Physics steps [s], comma-separated");
  app.add_option("--reference", reference_kind,
                 "The reference solution: model (RK4 of the controllers' model) or mujoco (MuJoCo's RK4, "
                 "checked against RK4 of the model over --check-duration)")
      ->check(CLI::IsMember({"model", "mujoco"}));
  app.add_option("--reference-step", reference_step, "The reference's step [s]");
  app.add_option("--check-step", check_step, "With --reference mujoco: RK4 of the model's step [s]");
  app.add_option(
      "--check-duration", check_duration,
      "With --reference mujoco: simulated seconds of its check against RK4 of the model (0: none)");
  app.add_option("--repeats", repeats, "Rounds of timed replays of every plant; the least counts")
      ->check(CLI::PositiveNumber);
  app.add_option("--out", out_path, "TSV file to write (default: stdout only)");
  CLI11_PARSE(app, argc, argv);

  try {
    const Scenario base = lagrange::config::loadScenario(config);
    if (base.flexible) throw std::runtime_error("flexible joints are not part of this study");
    if (duration <= 0.0) duration = base.duration;
    if (label.empty()) label = base.name;
    const double period = base.tickPeriod(), tolerance = base.metrics.tolerance;
    std::ostringstream table;
    table << "# arm " << label << ": " << config << ", " << duration << " s at " << base.plant.publish_rate
          << " Hz, tolerance " << tolerance << " rad\n";
    const auto gapText = [&](const Gap& g) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.3g rad (largest at t = %.3f s)", g.value,
                    static_cast<double>(g.tick) * period);
      return std::string(buf);
    };
    // RK4 of the model at `step` for `ticks` ticks (the scenario's substeps say the step).
    const auto modelRun = [&](double step, long long ticks) {
      const Scenario s = scenarioFor(config, duration, "mujoco", step);
      ModelRk4Plant plant(s, period / s.substepsPerTick());
      return closedLoop(s, plant, ticks);
    };

    const std::vector<double> steps = parseList(steps_text);
    // The reference solution over the whole run.
    const Scenario ref_s = scenarioFor(config, duration, "mujoco", reference_step);
    Trajectory ref;
    if (reference_kind == "model") {
      ref = modelRun(reference_step, ref_s.lastTick());
    } else {
      EnginePlant plant(ref_s);
      ref = closedLoop(ref_s, plant, ref_s.lastTick());
    }
    if (!ref.stopped.empty()) throw std::runtime_error("the reference run stopped: " + ref.stopped);
    const Convergence ref_c = convergence(ref.error, period, tolerance);
    if (!ref_c.interpolated) throw std::runtime_error("the reference run does not converge");
    table << "# reference: " << (reference_kind == "model" ? "RK4 of the model" : "MuJoCo RK4") << " at "
          << reference_step << " s: convergence time " << fmt(ref_c.interpolated) << " s (sampled "
          << fmt(ref_c.sampled) << " s), " << fmt(ref.loop_cpu, "%.1f") << " CPU s\n";
    std::fprintf(stderr, "%s: the reference converges at %.6f s (%.1f CPU s)\n", label.c_str(),
                 *ref_c.interpolated, ref.loop_cpu);

    // The loop here is the product's: the scenario as shipped (its own engine
    // and step) through wiring::simulateInProcess gives the same numbers.
    {
      const Scenario s =
          lagrange::config::loadScenario(config, {"mode=inproc", "duration=" + fmt(duration, "%.17g")});
      EnginePlant plant(s);
      const Trajectory mine = closedLoop(s, plant, s.lastTick());
      const auto product = lagrange::wiring::simulateInProcess(s, nullptr, nullptr, nullptr);
      table << "# this loop against wiring::simulateInProcess (the scenario's own engine and step, "
            << s.plant.physics_step << " s): convergence time "
            << fmt(convergence(mine.error, period, tolerance).sampled) << " and "
            << fmt(product.tracking.convergence_time) << " s, final error " << fmt(mine.error.back(), "%.17g")
            << " and " << fmt(product.tracking.final_error, "%.17g") << " rad\n";
    }

    // A MuJoCo reference checked against RK4 of the model, on the run's start.
    if (reference_kind == "mujoco" && check_duration > 0.0) {
      const long long ticks = std::llround(std::min(check_duration, duration) / period);
      const Trajectory model = modelRun(check_step, ticks);
      table << "# check: RK4 of the model at " << check_step << " s over the first "
            << static_cast<double>(ticks) * period
            << " s: max |q_reference - q_model| = " << gapText(maxGap(ref, model)) << "\n";
    }

    // Every engine and step: the closed loop for the accuracy, then the
    // plant's CPU in `repeats` rounds over all of them (the least of each), so
    // that a burst of other load on the machine spoils one round, not a row.
    struct Row {
      std::string engine;
      double step = 0.0;
      Scenario scenario;
      Trajectory run;
      double plant_cpu = std::numeric_limits<double>::infinity();
    };
    std::vector<Row> rows;
    for (const std::string& engine : {std::string("ode"), std::string("mujoco")}) {
      if (engines_text.find(engine) == std::string::npos) continue;
      for (const double step : steps) {
        Row row{engine, step, scenarioFor(config, duration, engine, step), {}};
        EnginePlant plant(row.scenario);
        row.run = closedLoop(row.scenario, plant, row.scenario.lastTick());
        std::fprintf(stderr, "%s: %s at %g s: %s\n", label.c_str(), engine.c_str(), step,
                     row.run.stopped.empty() ? "ran" : row.run.stopped.c_str());
        rows.push_back(std::move(row));
      }
    }
    for (int r = 0; r < repeats; ++r)
      for (Row& row : rows) row.plant_cpu = std::min(row.plant_cpu, plantCpu(row.scenario, row.run));

    table << "arm\tengine\tstep\tstatus\tconv_time\tconv_time_sampled\tconv_err_rel\tmax_traj_err\t"
             "plant_cpu_per_s\tloop_cpu_per_s\n";
    for (const Row& row : rows) {
      const Trajectory& run = row.run;
      const double simulated = static_cast<double>(run.tau.size()) * period;
      const Convergence c = convergence(run.error, period, tolerance);
      std::optional<double> rel;
      if (run.stopped.empty() && c.interpolated)
        rel = std::abs(*c.interpolated - *ref_c.interpolated) / *ref_c.interpolated;
      const std::string status = !run.stopped.empty() ? "diverged" : c.interpolated ? "converged" : "no_conv";
      char line[512];
      std::snprintf(line, sizeof line, "%s\t%s\t%.3g\t%s\t%s\t%s\t%s\t%s\t%.4g\t%.4g\n", label.c_str(),
                    row.engine.c_str(), row.step, status.c_str(), fmt(c.interpolated).c_str(),
                    fmt(c.sampled).c_str(), fmt(rel, "%.3e").c_str(),
                    fmt(maxGap(run, ref).value, "%.3e").c_str(), row.plant_cpu / simulated,
                    run.loop_cpu / simulated);
      table << line;
    }
    std::printf("%s", table.str().c_str());
    if (!out_path.empty()) std::ofstream(out_path) << table.str();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lagrange-bench-engines: %s\n", e.what());
    return 1;
  }
  return 0;
}
